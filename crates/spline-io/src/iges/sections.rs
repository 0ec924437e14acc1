//! The records of an IGES file: 80 columns, the section letter in column 73 and the
//! sequence number in columns 74–80; the five sections in order, checked against the
//! Terminate record.

use super::layout::{RECORD, Section, parse_error};
use spline_core::{Error, ErrorKind, Result};

/// The first byte that is not ASCII (or is a control character other than line breaks,
/// tabs and form feeds), as an error naming its line and column.
pub(super) fn check_ascii(bytes: &[u8]) -> Result<()> {
    let bad = |b: u8| !(b.is_ascii_graphic() || matches!(b, b' ' | b'\n' | b'\r' | b'\t' | 0x0c));
    if let Some(i) = bytes.iter().position(|&b| bad(b)) {
        let line = 1 + bytes[..i].iter().filter(|&&b| b == b'\n').count();
        let start = bytes[..i]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |k| k + 1);
        let what = if bytes[i].is_ascii() {
            "control character"
        } else {
            "non-ASCII byte"
        };
        return Err(Error::new(
            ErrorKind::Parse,
            format!(
                "IGES file line {line}: {what} 0x{:02X} in column {}; IGES files are ASCII",
                bytes[i],
                i - start + 1
            ),
        ));
    }
    Ok(())
}

/// The records of the five sections, each the text of columns 1–72.
pub(super) struct Sections<'a> {
    pub(super) global: Vec<&'a str>,
    pub(super) directory: Vec<&'a str>,
    pub(super) parameter: Vec<&'a str>,
    pub(super) terminate: Option<&'a str>,
}

/// The physical lines of the file: line breaks, or 80-column records without breaks.
pub(super) fn physical_lines(text: &str) -> Vec<&str> {
    let trimmed = text.trim_end_matches(['\n', '\r', '\u{1a}']);
    if !trimmed.contains('\n') && trimmed.len() > RECORD && trimmed.len() % RECORD == 0 {
        return (0..trimmed.len() / RECORD)
            .map(|k| &trimmed[k * RECORD..(k + 1) * RECORD])
            .collect();
    }
    trimmed
        .split('\n')
        .map(|l| l.strip_suffix('\r').unwrap_or(l))
        .collect()
}

pub(super) fn split_sections(text: &str) -> Result<Sections<'_>> {
    let order = |c: char| match c {
        'S' => Some((0, Section::Start)),
        'G' => Some((1, Section::Global)),
        'D' => Some((2, Section::Directory)),
        'P' => Some((3, Section::Parameter)),
        'T' => Some((4, Section::Terminate)),
        _ => None,
    };
    let mut sections = Sections {
        global: Vec::new(),
        directory: Vec::new(),
        parameter: Vec::new(),
        terminate: None,
    };
    let mut counts = [0usize; 5];
    let mut current = 0;
    for (k, line) in physical_lines(text).into_iter().enumerate() {
        let file_line = k + 1;
        let file_error = |message: String| {
            Error::new(
                ErrorKind::Parse,
                format!("IGES file line {file_line}: {message}"),
            )
        };
        if line.trim().is_empty() {
            continue;
        }
        if line.len() > RECORD {
            return Err(file_error(format!(
                "the record has {} columns; IGES records have {RECORD}",
                line.len()
            )));
        }
        if line.len() < 73 {
            return Err(file_error(format!(
                "the record has {} columns, too few for the section letter in column 73 \
                 (a fixed-format IGES file has 80-column records)",
                line.len()
            )));
        }
        let letter = char::from(line.as_bytes()[72]);
        let Some((rank, section)) = order(letter) else {
            return Err(file_error(match letter {
                'C' => "compressed ASCII IGES files are not supported".to_string(),
                'B' => "binary IGES files are not supported".to_string(),
                _ => format!("unknown section letter '{letter}' in column 73"),
            }));
        };
        if rank < current {
            return Err(file_error(format!(
                "a record of section {section} after a later section"
            )));
        }
        if rank == 4 && counts[4] > 0 {
            return Err(file_error("a second Terminate record".to_string()));
        }
        current = rank;
        counts[rank] += 1;
        let expected = counts[rank];
        let number = line[73..].trim();
        if number.parse::<usize>().ok() != Some(expected) {
            return Err(parse_error(
                section,
                expected,
                format!(
                    "sequence number '{number}' in columns 74–80, expected {expected} (a record is missing or out of order)"
                ),
            ));
        }
        let data = &line[..72];
        match section {
            Section::Start => {}
            Section::Global => sections.global.push(data),
            Section::Directory => sections.directory.push(data),
            Section::Parameter => sections.parameter.push(data),
            Section::Terminate => sections.terminate = Some(data),
        }
    }
    let Some(terminate) = sections.terminate else {
        return Err(Error::new(
            ErrorKind::Parse,
            format!(
                "IGES line {} ({}): the file ends without a Terminate (T) record (truncated?)",
                counts[current].max(1),
                ["S", "G", "D", "P", "T"][current]
            ),
        ));
    };
    check_terminate(terminate, &counts)?;
    if sections.global.is_empty() {
        return Err(parse_error(
            Section::Global,
            1,
            "the file has no Global section",
        ));
    }
    if sections.directory.len() % 2 != 0 {
        return Err(parse_error(
            Section::Directory,
            sections.directory.len(),
            format!(
                "{} Directory Entry records; each entity has two",
                sections.directory.len()
            ),
        ));
    }
    Ok(sections)
}

/// The Terminate record's counts against the records read.
pub(super) fn check_terminate(record: &str, counts: &[usize; 5]) -> Result<()> {
    for (k, letter) in ['S', 'G', 'D', 'P'].into_iter().enumerate() {
        let field = &record[8 * k..8 * k + 8];
        let ok = field.starts_with(letter);
        let value = field[1..].trim().parse::<usize>().ok();
        match value {
            Some(n) if ok => {
                if n != counts[k] {
                    return Err(parse_error(
                        Section::Terminate,
                        1,
                        format!(
                            "the Terminate record counts {n} {letter} records, the file has {} (truncated or damaged)",
                            counts[k]
                        ),
                    ));
                }
            }
            _ => {
                return Err(parse_error(
                    Section::Terminate,
                    1,
                    format!(
                        "field {} should be '{letter}' and a count, found '{}'",
                        k + 1,
                        field.trim()
                    ),
                ));
            }
        }
    }
    Ok(())
}
