//! Free-format parameters (the Global and Parameter Data sections): Hollerith strings,
//! integers and reals between the file's delimiters.

use super::layout::{GLOBAL_WIDTH, Section, parse_error};
use spline_core::Result;

/// One parameter: a Hollerith string or the raw text of a number (empty when defaulted),
/// with the sequence number of the record it starts on.
#[derive(Clone, Debug)]
pub(super) struct Token {
    pub(super) text: String,
    pub(super) string: bool,
    pub(super) line: usize,
}

/// Splits the free-format text `buffer` (records of `width` columns concatenated, the first
/// being record `first_line` of `section`) into parameters up to the record delimiter.
pub(super) fn tokenize(
    buffer: &[u8],
    width: usize,
    first_line: usize,
    section: Section,
    delimiters: (u8, u8),
    mut pos: usize,
) -> Result<Vec<Token>> {
    let (pd, rd) = delimiters;
    let line_of = |i: usize| first_line + i.min(buffer.len().saturating_sub(1)) / width;
    let mut tokens = Vec::new();
    loop {
        while pos < buffer.len() && buffer[pos] == b' ' {
            pos += 1;
        }
        if pos >= buffer.len() {
            return Err(parse_error(
                section,
                line_of(buffer.len()),
                format!(
                    "the parameters end without the record delimiter '{}' (truncated?)",
                    char::from(rd)
                ),
            ));
        }
        let start = pos;
        let digits_end = (pos..buffer.len())
            .find(|&i| !buffer[i].is_ascii_digit())
            .unwrap_or(buffer.len());
        let token = if digits_end > pos
            && digits_end < buffer.len()
            && matches!(buffer[digits_end], b'H' | b'h')
        {
            let count: usize = std::str::from_utf8(&buffer[pos..digits_end])
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(usize::MAX);
            let text_start = digits_end + 1;
            if count > buffer.len() - text_start {
                return Err(parse_error(
                    section,
                    line_of(start),
                    format!(
                        "a Hollerith string of {} characters runs past the end of the parameters",
                        &String::from_utf8_lossy(&buffer[pos..digits_end])
                    ),
                ));
            }
            pos = text_start + count;
            while pos < buffer.len() && buffer[pos] == b' ' {
                pos += 1;
            }
            Token {
                text: String::from_utf8_lossy(&buffer[text_start..text_start + count]).into_owned(),
                string: true,
                line: line_of(start),
            }
        } else {
            while pos < buffer.len() && buffer[pos] != pd && buffer[pos] != rd {
                pos += 1;
            }
            Token {
                text: String::from_utf8_lossy(&buffer[start..pos])
                    .trim()
                    .to_string(),
                string: false,
                line: line_of(start),
            }
        };
        if pos >= buffer.len() {
            continue; // reported above
        }
        let delimiter = buffer[pos];
        if delimiter != pd && delimiter != rd {
            return Err(parse_error(
                section,
                line_of(pos),
                format!(
                    "'{}' after a Hollerith string, expected the delimiter '{}' or '{}'",
                    char::from(delimiter),
                    char::from(pd),
                    char::from(rd)
                ),
            ));
        }
        pos += 1;
        tokens.push(token);
        if delimiter == rd {
            return Ok(tokens);
        }
    }
}

/// A real number in IGES form (`1.5`, `-2.`, `.5`, `1.5E-07`, `1.5D-07`; empty is the
/// default 0).
pub(super) fn parse_real(token: &Token, section: Section, what: &str) -> Result<f64> {
    if token.string {
        return Err(parse_error(
            section,
            token.line,
            format!("{what}: a string where a number is expected"),
        ));
    }
    let text = token.text.as_str();
    if text.is_empty() {
        return Ok(0.0);
    }
    let valid = text
        .bytes()
        .all(|b| b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.' | b'E' | b'e' | b'D' | b'd'))
        && text.bytes().any(|b| b.is_ascii_digit());
    let normal: String = text
        .chars()
        .map(|c| if matches!(c, 'D' | 'd') { 'E' } else { c })
        .collect();
    let value = if valid {
        normal.parse::<f64>().ok()
    } else {
        None
    };
    match value {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(parse_error(
            section,
            token.line,
            format!("{what}: {text} is out of the range of double precision"),
        )),
        None => Err(parse_error(
            section,
            token.line,
            format!("{what}: '{text}' is not a number"),
        )),
    }
}

/// An integer (empty is the default 0).
pub(super) fn parse_int(token: &Token, section: Section, what: &str) -> Result<i64> {
    if token.string {
        return Err(parse_error(
            section,
            token.line,
            format!("{what}: a string where an integer is expected"),
        ));
    }
    let text = token.text.as_str();
    integer_text(text).ok_or_else(|| {
        parse_error(
            section,
            token.line,
            format!("{what}: '{text}' is not an integer"),
        )
    })
}

/// The integer an IGES field's text holds (a leading `+` allowed; empty is the default 0),
/// `None` if it is not one.
pub(super) fn integer_text(text: &str) -> Option<i64> {
    if text.is_empty() {
        return Some(0);
    }
    text.strip_prefix('+').unwrap_or(text).parse::<i64>().ok()
}

/// The Global section: its delimiters (the rest is checked for syntax only).
pub(super) fn parse_global(records: &[&str]) -> Result<(u8, u8)> {
    let buffer: Vec<u8> = records.iter().flat_map(|r| r.bytes()).collect();
    let mut pos = 0;
    while pos < buffer.len() && buffer[pos] == b' ' {
        pos += 1;
    }
    let hollerith_char = |pos: usize| -> Option<u8> {
        (buffer.len() > pos + 2 && buffer[pos] == b'1' && matches!(buffer[pos + 1], b'H' | b'h'))
            .then(|| buffer[pos + 2])
    };
    let bad = |message: &str| parse_error(Section::Global, 1, message);
    let pd = if let Some(c) = hollerith_char(pos) {
        pos += 3;
        c
    } else if buffer.get(pos) == Some(&b',') {
        b','
    } else {
        return Err(bad(
            "the Global section must start with the parameter delimiter (1H, or a defaulted ',')",
        ));
    };
    if buffer.get(pos) != Some(&pd) {
        return Err(bad("the parameter delimiter must be followed by itself"));
    }
    pos += 1;
    while pos < buffer.len() && buffer[pos] == b' ' {
        pos += 1;
    }
    let rd = if let Some(c) = hollerith_char(pos) {
        pos += 3;
        c
    } else if buffer.get(pos) == Some(&pd) {
        b';'
    } else {
        return Err(bad(
            "the second Global parameter must be the record delimiter (1H; or defaulted)",
        ));
    };
    if pd == rd || matches!(pd, b' ' | b'0'..=b'9' | b'H' | b'+' | b'-' | b'.') {
        return Err(bad(
            "the parameter and record delimiters are invalid or equal",
        ));
    }
    if buffer.get(pos) == Some(&rd) {
        return Ok((pd, rd));
    }
    if buffer.get(pos) != Some(&pd) {
        return Err(bad(
            "the record delimiter must be followed by the parameter delimiter",
        ));
    }
    let tokens = tokenize(&buffer, GLOBAL_WIDTH, 1, Section::Global, (pd, rd), pos + 1)?;
    // Fields 3 onwards: check the numbers that matter for geometry.
    for (index, what) in [
        (10, "model space scale (field 13)"),
        (16, "minimum resolution (field 19)"),
    ] {
        if let Some(t) = tokens.get(index) {
            parse_real(t, Section::Global, what)?;
        }
    }
    if let Some(t) = tokens.get(11) {
        parse_int(t, Section::Global, "unit flag (field 14)")?;
    }
    Ok((pd, rd))
}

#[cfg(test)]
mod tests {
    use super::{Section, Token, parse_real};
    use crate::real::real;

    #[test]
    fn reals_written_by_real_read_back_exactly_and_every_form_reads() {
        let cases = [
            0.1,
            1.0 / 3.0,
            -0.0,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            1e16,
            1e-5,
            1e16 - 2.0,
            -123_456.789,
            2.0,
        ];
        for x in cases {
            let s = real(x);
            assert!(s.contains('.'), "{s}");
            assert!(s.len() <= 24, "{s}");
            let t = Token {
                text: s.clone(),
                string: false,
                line: 1,
            };
            assert_eq!(
                parse_real(&t, Section::Parameter, "x").unwrap().to_bits(),
                x.to_bits(),
                "{s}"
            );
        }
        for (text, value) in [
            ("1.5D-07", 1.5e-7),
            ("1.5d+3", 1500.0),
            ("-2.", -2.0),
            (".5", 0.5),
            ("+3", 3.0),
            ("", 0.0),
            ("1.E2", 100.0),
        ] {
            let t = Token {
                text: text.to_string(),
                string: false,
                line: 1,
            };
            assert_eq!(
                parse_real(&t, Section::Parameter, "x").unwrap(),
                value,
                "{text}"
            );
        }
        for text in ["1.2.3", "inf", "NaN", "1E999", "0x10", "-"] {
            let t = Token {
                text: text.to_string(),
                string: false,
                line: 7,
            };
            let e = parse_real(&t, Section::Parameter, "knot").unwrap_err();
            assert!(e.message().starts_with("IGES line 7 (P): knot"), "{e}");
        }
    }
}
