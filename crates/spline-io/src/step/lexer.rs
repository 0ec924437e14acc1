//! The tokens of the exchange structure (ISO 10303-21 §5–6): keywords, instance names,
//! numbers, strings with their encodings, enumerations, punctuation, comments skipped; each
//! error names its line.

use super::instance::error_at;
use spline_core::Result;

/// The tokens of the exchange structure.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Token {
    Keyword(String),
    Instance(u64),
    Integer(i64),
    Real(f64),
    Text(String),
    Enumeration(String),
    Open,
    Close,
    Comma,
    Semicolon,
    Equals,
    Dollar,
    Star,
}

pub(super) struct Lexer<'a> {
    bytes: &'a [u8],
    at: usize,
    /// The line of the next byte.
    pub(super) line: usize,
}

impl<'a> Lexer<'a> {
    pub(super) fn new(bytes: &'a [u8]) -> Self {
        Self {
            bytes,
            at: 0,
            line: 1,
        }
    }

    fn skip_space(&mut self) -> Result<()> {
        loop {
            match self.bytes.get(self.at) {
                Some(b'\n') => {
                    self.line += 1;
                    self.at += 1;
                }
                Some(b' ' | b'\t' | b'\r') => self.at += 1,
                Some(b'/') if self.bytes.get(self.at + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.at += 2;
                    loop {
                        match self.bytes.get(self.at) {
                            None => return Err(error_at(start, "a comment is not closed (*/)")),
                            Some(b'*') if self.bytes.get(self.at + 1) == Some(&b'/') => {
                                self.at += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.at += 1;
                            }
                            Some(_) => self.at += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    /// The next token, `None` at the end of the input.
    pub(super) fn next(&mut self) -> Result<Option<Token>> {
        self.skip_space()?;
        let Some(&c) = self.bytes.get(self.at) else {
            return Ok(None);
        };
        let single = match c {
            b'(' => Some(Token::Open),
            b')' => Some(Token::Close),
            b',' => Some(Token::Comma),
            b';' => Some(Token::Semicolon),
            b'=' => Some(Token::Equals),
            b'$' => Some(Token::Dollar),
            b'*' => Some(Token::Star),
            _ => None,
        };
        if let Some(token) = single {
            self.at += 1;
            return Ok(Some(token));
        }
        match c {
            b'#' => {
                self.at += 1;
                let digits = self.take(|b| b.is_ascii_digit());
                let id = digits
                    .parse::<u64>()
                    .map_err(|_| error_at(self.line, format!("bad instance name #{digits}")))?;
                Ok(Some(Token::Instance(id)))
            }
            b'\'' => self.text().map(Some),
            b'.' if self
                .bytes
                .get(self.at + 1)
                .is_some_and(u8::is_ascii_alphabetic) =>
            {
                self.at += 1;
                let name = self.take(|b| b.is_ascii_alphanumeric() || b == b'_');
                if self.bytes.get(self.at) != Some(&b'.') {
                    return Err(error_at(
                        self.line,
                        format!("enumeration .{name} is not closed by a dot"),
                    ));
                }
                self.at += 1;
                Ok(Some(Token::Enumeration(name.to_ascii_uppercase())))
            }
            b'+' | b'-' | b'.' | b'0'..=b'9' => self.number().map(Some),
            b'!' | b'A'..=b'Z' | b'a'..=b'z' | b'_' => {
                let start = self.at;
                self.at += 1;
                let rest = self.take(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-');
                let word = format!("{}{rest}", self.bytes[start] as char);
                Ok(Some(Token::Keyword(word.to_ascii_uppercase())))
            }
            c if !c.is_ascii() => Err(error_at(
                self.line,
                "a byte outside ASCII outside a string (ISO 10303-21 files are ASCII; other characters are encoded in strings as \\X2\\…\\X0\\)",
            )),
            c => Err(error_at(
                self.line,
                format!("unexpected character {:?}", c as char),
            )),
        }
    }

    fn take(&mut self, keep: impl Fn(u8) -> bool) -> String {
        let start = self.at;
        while self.bytes.get(self.at).is_some_and(|&b| keep(b)) {
            self.at += 1;
        }
        String::from_utf8_lossy(&self.bytes[start..self.at]).into_owned()
    }

    fn number(&mut self) -> Result<Token> {
        let start = self.at;
        if matches!(self.bytes.get(self.at), Some(b'+' | b'-')) {
            self.at += 1;
        }
        let mut real = false;
        while let Some(&b) = self.bytes.get(self.at) {
            match b {
                b'0'..=b'9' => self.at += 1,
                b'.' => {
                    real = true;
                    self.at += 1;
                }
                b'E' | b'e' | b'D' | b'd' => {
                    real = true;
                    self.at += 1;
                    if matches!(self.bytes.get(self.at), Some(b'+' | b'-')) {
                        self.at += 1;
                    }
                }
                _ => break,
            }
        }
        let text = String::from_utf8_lossy(&self.bytes[start..self.at]).replace(['D', 'd'], "E");
        let bad = || error_at(self.line, format!("bad number {text:?}"));
        if real {
            let x: f64 = text.parse().map_err(|_| bad())?;
            if !x.is_finite() {
                return Err(error_at(
                    self.line,
                    format!("number {text} is out of range"),
                ));
            }
            Ok(Token::Real(x))
        } else {
            text.parse().map(Token::Integer).map_err(|_| bad())
        }
    }

    /// A string: `''` is a quote, `\\` a backslash, `\X2\…\X0\` UCS-2 code units in hex,
    /// `\X\hh` one byte in hex, `\S\c` a character of the upper half of ISO 8859-1.
    fn text(&mut self) -> Result<Token> {
        let start = self.line;
        self.at += 1;
        let mut raw = Vec::new();
        loop {
            match self.bytes.get(self.at) {
                None => return Err(error_at(start, "a string is not closed")),
                Some(b'\'') if self.bytes.get(self.at + 1) == Some(&b'\'') => {
                    raw.push(b'\'');
                    self.at += 2;
                }
                Some(b'\'') => {
                    self.at += 1;
                    break;
                }
                Some(&b) => {
                    if b == b'\n' {
                        self.line += 1;
                    } else if !b.is_ascii() {
                        return Err(error_at(
                            self.line,
                            "a byte outside ASCII in a string (encode it as \\X2\\…\\X0\\)",
                        ));
                    }
                    if b != b'\n' && b != b'\r' {
                        raw.push(b);
                    }
                    self.at += 1;
                }
            }
        }
        decode_text(&raw)
            .map(Token::Text)
            .map_err(|m| error_at(start, m))
    }
}

fn decode_text(raw: &[u8]) -> std::result::Result<String, String> {
    let mut out = String::with_capacity(raw.len());
    let mut i = 0;
    let hex =
        |s: &[u8]| -> Option<u32> { u32::from_str_radix(std::str::from_utf8(s).ok()?, 16).ok() };
    while i < raw.len() {
        if raw[i] != b'\\' {
            out.push(raw[i] as char);
            i += 1;
            continue;
        }
        let rest = &raw[i..];
        if rest.starts_with(b"\\\\") {
            out.push('\\');
            i += 2;
        } else if rest.starts_with(b"\\X2\\") {
            i += 4;
            let end = raw[i..]
                .windows(4)
                .position(|w| w == b"\\X0\\")
                .ok_or("\\X2\\ without \\X0\\ in a string")?;
            let units: Vec<u16> = raw[i..i + end]
                .chunks(4)
                .map(|c| hex(c).and_then(|v| u16::try_from(v).ok()))
                .collect::<Option<_>>()
                .ok_or("bad hex digits after \\X2\\ in a string")?;
            out.push_str(&String::from_utf16_lossy(&units));
            i += end + 4;
        } else if rest.starts_with(b"\\X\\") && rest.len() >= 5 {
            let v = hex(&rest[3..5]).ok_or("bad hex digits after \\X\\ in a string")?;
            out.push(char::from_u32(v).unwrap_or('\u{fffd}'));
            i += 5;
        } else if rest.starts_with(b"\\S\\") && rest.len() >= 4 {
            out.push(char::from_u32(u32::from(rest[3]) + 128).unwrap_or('\u{fffd}'));
            i += 4;
        } else {
            // A lone backslash (or a directive this reader does not decode): kept as it is.
            out.push('\\');
            i += 1;
        }
    }
    Ok(out)
}
