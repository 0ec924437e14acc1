//! Reading objects and points, writing JSON: the tool's side of the exchange format.

use nalgebra::SVector;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use serde_json::value::RawValue;
use spline_core::{Error, ErrorKind, Result};
use spline_io::exchange::{parse_json, serde_message};
use spline_io::points::parse_points;
use std::io::{Read, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// The largest number of coordinates the tool accepts for control points and data points.
pub const MAX_DIM: usize = 8;

/// The tool's point type: coordinates padded with zeros to [`MAX_DIM`]. Zero coordinates
/// stay zero under every affine combination and do not change lengths or angles, so one
/// instantiation of the library serves every dimension `1 ≤ d ≤ MAX_DIM` exactly.
pub type Pt = SVector<f64, MAX_DIM>;

/// Reads a whole file, or standard input for `-`.
pub fn read_text(path: &str) -> Result<String> {
    if path == "-" {
        let mut text = String::new();
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| Error::io("read standard input", e))?;
        Ok(text)
    } else {
        std::fs::read_to_string(path)
            .map_err(|e| Error::io(format_args!("read {path}"), e).with_file(path))
    }
}

/// Reads a JSON document from a file or `-`.
pub fn read_json(path: &str) -> Result<Value> {
    let text = read_text(path)?;
    parse_json(&text).map_err(|e| {
        Error::new(
            ErrorKind::Parse,
            format!("{path} is not valid JSON: {}", serde_message(e.message())),
        )
    })
}

/// The longest piece of a command-line value that a message quotes.
const QUOTE_LIMIT: usize = 40;

/// A command-line value as messages quote it: whole when short, its beginning otherwise.
pub fn quote(text: &str) -> String {
    if text.chars().count() <= QUOTE_LIMIT {
        format!("{text:?}")
    } else {
        let head: String = text.chars().take(QUOTE_LIMIT).collect();
        format!("{head:?}… ({} characters)", text.chars().count())
    }
}

/// Parses the JSON value of a command-line option. The message names the entry that could
/// not be read (`--at: entry 3: …`) and quotes at most the beginning of the value.
pub fn parse_arg<T: DeserializeOwned>(option: &str, text: &str) -> Result<T> {
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let value: T = serde_path_to_error::deserialize(&mut deserializer).map_err(|e| {
        let place = entry_name(&e.path().to_string());
        let what = serde_message(&e.inner().to_string());
        let message = if e.inner().is_syntax() || e.inner().is_eof() {
            format!("{option}: {} is not valid JSON: {what}", quote(text))
        } else if place.is_empty() {
            format!("{option}: {what}")
        } else {
            format!("{option}: {place}: {what}")
        };
        Error::new(ErrorKind::Parse, message)
    })?;
    deserializer.end().map_err(|e| {
        Error::new(
            ErrorKind::Parse,
            format!(
                "{option}: {} is not valid JSON: {}",
                quote(text),
                serde_message(&e.to_string())
            ),
        )
    })?;
    Ok(value)
}

/// `[3]` → `entry 3`, `[3][1]` → `entry 3, coordinate 1`, `.` → nothing.
fn entry_name(path: &str) -> String {
    if path == "." {
        return String::new();
    }
    let indices: Vec<&str> = path.split(['[', ']']).filter(|s| !s.is_empty()).collect();
    match indices.as_slice() {
        [i] => format!("entry {i}"),
        [i, j] => format!("entry {i}, item {j}"),
        _ => format!("at {path}"),
    }
}

/// Set when standard output turned out to be a closed pipe: the tool then ends quietly.
static OUTPUT_CLOSED: AtomicBool = AtomicBool::new(false);

/// Whether standard output was a closed pipe (see [`write_stdout`]).
pub fn output_closed() -> bool {
    OUTPUT_CLOSED.load(Ordering::Relaxed)
}

/// Checks that standard output is open: with a closed descriptor the standard library
/// drops everything written, which would lose the output and still exit with 0.
///
/// # Errors
/// [`ErrorKind::Io`] when standard output is closed.
///
/// The Rust runtime reopens a standard descriptor that was closed at start-up on
/// `/dev/null` for reading and writing; a shell redirection (`> /dev/null`) opens it for
/// writing only. On Linux the two are told apart by `/proc/self/fdinfo/1`.
pub fn check_stdout_open() -> Result<()> {
    use std::os::fd::AsFd;
    let closed = || {
        Error::new(
            ErrorKind::Io,
            "standard output is closed; nothing can be printed",
        )
    };
    if std::io::stdout().as_fd().try_clone_to_owned().is_err() {
        return Err(closed());
    }
    let is_null = std::fs::read_link("/proc/self/fd/1")
        .is_ok_and(|target| target == std::path::Path::new("/dev/null"));
    if is_null {
        let read_write = std::fs::read_to_string("/proc/self/fdinfo/1").is_ok_and(|info| {
            info.lines()
                .find_map(|l| l.strip_prefix("flags:"))
                .and_then(|flags| u32::from_str_radix(flags.trim(), 8).ok())
                .is_some_and(|flags| flags & 0o3 == 0o2)
        });
        if read_write {
            return Err(closed());
        }
    }
    Ok(())
}

/// Writes a line on standard output. A closed pipe (the reader has gone, as with `| head`)
/// sets [`output_closed`] and returns an error that the tool does not print; any other
/// failure (a full disk) is an error.
///
/// # Errors
/// [`ErrorKind::Io`] when the output cannot be written.
pub fn write_stdout(bytes: &[u8]) -> Result<()> {
    write_stdout_stream(|write| write(bytes))
}

/// Writes a line on standard output in pieces, as `produce` makes them (so that a large
/// output is never held whole), with the error handling of [`write_stdout`]. An error of
/// `produce` after some pieces were written leaves them written.
///
/// # Errors
/// The errors of `produce`; [`ErrorKind::Io`] when the output cannot be written.
pub fn write_stdout_stream(
    produce: impl FnOnce(&mut dyn FnMut(&[u8]) -> Result<()>) -> Result<()>,
) -> Result<()> {
    let stdout = std::io::stdout().lock();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout);
    let failed = |e: std::io::Error| {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            OUTPUT_CLOSED.store(true, Ordering::Relaxed);
        }
        Error::io("write to standard output", e)
    };
    produce(&mut |bytes: &[u8]| out.write_all(bytes).map_err(failed))?;
    out.write_all(b"\n")
        .and_then(|()| out.flush())
        .map_err(failed)
}

/// Writes a whole file opened earlier; a full disk is a one-line error that names the file.
///
/// # Errors
/// [`ErrorKind::Io`] when the file cannot be written.
pub fn write_file(mut file: std::fs::File, path: &str, bytes: &[u8]) -> Result<()> {
    file.write_all(bytes)
        .and_then(|()| file.flush())
        .map_err(|e| Error::io(format_args!("write {path}"), e).with_file(path))
}

/// Creates an output file before the work that fills it, so that a bad path fails at once.
///
/// # Errors
/// [`ErrorKind::Io`] when the file cannot be created.
pub fn create_file(path: &str) -> Result<std::fs::File> {
    std::fs::File::create(path)
        .map_err(|e| Error::io(format_args!("write {path}"), e).with_file(path))
}

/// A JSON formatter that refuses to write `null`: the exchange format has no nulls, and
/// serde_json writes NaN and infinities as `null`.
struct FiniteOnly;

impl serde_json::ser::Formatter for FiniteOnly {
    fn write_null<W: ?Sized + Write>(&mut self, _writer: &mut W) -> std::io::Result<()> {
        Err(std::io::Error::other(NON_FINITE))
    }
}

const NON_FINITE: &str =
    "the result holds numbers beyond the range of floating point (±1.8e308); nothing printed";

/// Encodes a value as one line of JSON; refuses non-finite numbers.
///
/// # Errors
/// [`ErrorKind::NonFinite`] if the value holds NaN or an infinity.
pub fn encode(value: &impl Serialize) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut serializer = serde_json::Serializer::with_formatter(&mut bytes, FiniteOnly);
    value.serialize(&mut serializer).map_err(|e| {
        if e.is_io() {
            Error::new(ErrorKind::NonFinite, NON_FINITE)
        } else {
            Error::new(
                ErrorKind::InvalidArgument,
                format!("cannot encode output: {e}"),
            )
        }
    })?;
    Ok(bytes)
}

/// JSON text encoded once.
pub type Json = Box<RawValue>;

/// A value encoded once (see [`encode`]), to be embedded in a larger output without a
/// second copy as a `serde_json::Value` tree.
///
/// # Errors
/// As [`encode`].
pub fn raw(value: &impl Serialize) -> Result<Box<RawValue>> {
    let text = String::from_utf8(encode(value)?)
        .map_err(|_| Error::new(ErrorKind::InvalidArgument, "cannot encode output as UTF-8"))?;
    RawValue::from_string(text).map_err(|e| {
        Error::new(
            ErrorKind::InvalidArgument,
            format!("cannot encode output: {e}"),
        )
    })
}

/// Prints a value as one line of JSON; refuses to print non-finite numbers.
///
/// # Errors
/// As [`encode`] and [`write_stdout`].
pub fn print_json(value: &impl Serialize) -> Result<()> {
    write_stdout(&encode(value)?)
}

/// The largest number of numbers that one output may hold when its size is chosen by a count
/// on the command line (`eval --derivatives`, `basis --derivatives`): about 200 MB of JSON.
pub const MAX_OUTPUT_NUMBERS: usize = 10_000_000;

/// Checks the size of an output chosen by counts before anything is computed.
///
/// # Errors
/// [`ErrorKind::InvalidArgument`] above [`MAX_OUTPUT_NUMBERS`] (or on overflow), with
/// `(MAX_OUTPUT_NUMBERS, count)` as [`Error::counts`] when the count fits a `usize`.
pub fn check_output_size(what: &str, factors: &[usize]) -> Result<()> {
    let total = factors
        .iter()
        .try_fold(1usize, |acc, &f| acc.checked_mul(f));
    match total {
        Some(n) if n <= MAX_OUTPUT_NUMBERS => Ok(()),
        _ => {
            let e = Error::new(
                ErrorKind::InvalidArgument,
                format!(
                    "{what} would print {} numbers, more than the limit {MAX_OUTPUT_NUMBERS}",
                    total.map_or_else(|| "too many".to_string(), |n| n.to_string())
                ),
            );
            // The count, when it does not overflow.
            Err(match total {
                Some(n) => e.with_counts(MAX_OUTPUT_NUMBERS, n),
                None => e,
            })
        }
    }
}

/// Pads a point to [`MAX_DIM`] coordinates.
pub fn pad(row: &[f64]) -> Result<Pt> {
    if row.is_empty() || row.len() > MAX_DIM {
        return Err(Error::new(
            ErrorKind::DimensionMismatch,
            format!(
                "points must have 1 to {MAX_DIM} coordinates, got {}",
                row.len()
            ),
        ));
    }
    let mut p = Pt::zeros();
    p.as_mut_slice()[..row.len()].copy_from_slice(row);
    Ok(p)
}

/// The first `dim` coordinates of a padded point.
pub fn unpad(p: &Pt, dim: usize) -> Vec<f64> {
    p.as_slice()[..dim].to_vec()
}

/// Reads a point file (JSON array of arrays, or text; see
/// [`spline_io::points::parse_points`]).
///
/// # Errors
/// [`ErrorKind::Io`] for an unreadable file; the errors of `parse_points`, naming the file.
pub fn read_points(path: &str) -> Result<Vec<Vec<f64>>> {
    parse_points(&read_text(path)?).map_err(|e| e.context(path))
}
