//! The parser of the exchange structure: the header skipped, the instances of the `DATA`
//! sections kept by `#id` with their line and records, in one pass.

use super::instance::{Instance, MAX_NESTING, Param, error_at};
use super::lexer::{Lexer, Token};
use spline_core::Result;
use std::collections::HashMap;

struct Parser<'a> {
    lexer: Lexer<'a>,
    peeked: Option<(Token, usize)>,
}

impl<'a> Parser<'a> {
    fn next(&mut self) -> Result<Option<(Token, usize)>> {
        if let Some(t) = self.peeked.take() {
            return Ok(Some(t));
        }
        let token = self.lexer.next()?;
        Ok(token.map(|t| (t, self.lexer.line)))
    }

    fn peek(&mut self) -> Result<Option<&Token>> {
        if self.peeked.is_none() {
            self.peeked = self.next()?;
        }
        Ok(self.peeked.as_ref().map(|(t, _)| t))
    }

    fn expect(&mut self, want: &Token, what: &str) -> Result<usize> {
        match self.next()? {
            Some((t, line)) if &t == want => Ok(line),
            Some((t, line)) => Err(error_at(line, format!("expected {what}, found {t:?}"))),
            None => Err(error_at(
                self.lexer.line,
                format!("the file ends where {what} was expected"),
            )),
        }
    }

    /// `( param, param, … )`, the opening parenthesis already read.
    fn params(&mut self, depth: usize) -> Result<Vec<Param>> {
        if depth > MAX_NESTING {
            return Err(error_at(self.lexer.line, "lists nest too deep"));
        }
        let mut out = Vec::new();
        if self.peek()? == Some(&Token::Close) {
            self.next()?;
            return Ok(out);
        }
        loop {
            out.push(self.param(depth)?);
            match self.next()? {
                Some((Token::Comma, _)) => {}
                Some((Token::Close, _)) => return Ok(out),
                Some((t, line)) => {
                    return Err(error_at(
                        line,
                        format!("expected , or ) in a list, found {t:?}"),
                    ));
                }
                None => return Err(error_at(self.lexer.line, "the file ends inside a list")),
            }
        }
    }

    /// `NAME(param, …)` of instance `#id`, the name already read as `token`.
    fn record(&mut self, id: u64, token: Option<(Token, usize)>) -> Result<(String, Vec<Param>)> {
        match token {
            Some((Token::Keyword(name), _)) => {
                self.expect(&Token::Open, &format!("( after {name}"))?;
                Ok((name, self.params(1)?))
            }
            Some((t, l)) => Err(error_at(
                l,
                format!("#{id}: expected an entity name, found {t:?}"),
            )),
            None => Err(error_at(
                self.lexer.line,
                format!("the file ends inside #{id}"),
            )),
        }
    }

    fn param(&mut self, depth: usize) -> Result<Param> {
        let Some((token, line)) = self.next()? else {
            return Err(error_at(self.lexer.line, "the file ends inside a list"));
        };
        Ok(match token {
            Token::Integer(i) => Param::Integer(i),
            Token::Real(x) => Param::Real(x),
            Token::Text(s) => Param::Text(s),
            Token::Enumeration(e) => Param::Enumeration(e),
            Token::Instance(id) => Param::Reference(id),
            Token::Dollar => Param::Unset,
            Token::Star => Param::Derived,
            Token::Open => Param::List(self.params(depth + 1)?),
            Token::Keyword(name) => {
                self.expect(&Token::Open, "( after a type name")?;
                let mut inner = self.params(depth + 1)?;
                if inner.len() != 1 {
                    return Err(error_at(
                        line,
                        format!("typed parameter {name} needs one value"),
                    ));
                }
                Param::Typed(name, Box::new(inner.remove(0)))
            }
            t => return Err(error_at(line, format!("unexpected {t:?} in a list"))),
        })
    }
}

/// The instances of the `DATA` sections.
pub(super) fn parse(bytes: &[u8]) -> Result<HashMap<u64, Instance>> {
    let mut parser = Parser {
        lexer: Lexer::new(bytes),
        peeked: None,
    };
    match parser.next()? {
        Some((Token::Keyword(k), _)) if k == "ISO-10303-21" => {}
        Some((_, line)) => {
            return Err(error_at(
                line,
                "not a STEP file: it does not start with ISO-10303-21;",
            ));
        }
        None => return Err(error_at(1, "the file is empty")),
    }
    parser.expect(&Token::Semicolon, "; after ISO-10303-21")?;
    let mut instances = HashMap::new();
    let mut in_data = false;
    loop {
        let Some((token, line)) = parser.next()? else {
            return Err(error_at(
                parser.lexer.line,
                "the file ends before END-ISO-10303-21;",
            ));
        };
        match token {
            Token::Keyword(k) if k == "END-ISO-10303-21" => return Ok(instances),
            Token::Keyword(k) if k == "DATA" => {
                // DATA; or DATA(parameters);
                if parser.peek()? == Some(&Token::Open) {
                    parser.next()?;
                    parser.params(1)?;
                }
                parser.expect(&Token::Semicolon, "; after DATA")?;
                in_data = true;
            }
            Token::Keyword(k) if k == "ENDSEC" => {
                parser.expect(&Token::Semicolon, "; after ENDSEC")?;
                in_data = false;
            }
            Token::Instance(id) if in_data => {
                parser.expect(&Token::Equals, &format!("= after #{id}"))?;
                let mut records = Vec::new();
                match parser.next()? {
                    // A complex instance: `(NAME(…) NAME(…) …)`.
                    Some((Token::Open, _)) => loop {
                        match parser.next()? {
                            Some((Token::Close, _)) => break,
                            token => records.push(parser.record(id, token)?),
                        }
                    },
                    token => records.push(parser.record(id, token)?),
                }
                parser.expect(&Token::Semicolon, &format!("; after #{id}"))?;
                if instances.insert(id, Instance { line, records }).is_some() {
                    return Err(error_at(line, format!("#{id} is defined twice")));
                }
            }
            Token::Keyword(_) if !in_data => {
                // A header entity or another section: skip to its semicolon, lists included.
                loop {
                    match parser.next()? {
                        Some((Token::Semicolon, _)) => break,
                        Some((Token::Open, _)) => {
                            parser.params(1)?;
                        }
                        Some(_) => {}
                        None => {
                            return Err(error_at(
                                parser.lexer.line,
                                "the file ends inside its header",
                            ));
                        }
                    }
                }
            }
            t => return Err(error_at(line, format!("unexpected {t:?}"))),
        }
    }
}
