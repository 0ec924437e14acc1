//! JSON values decoded into records, with messages in JSON's words that name the field.

use serde::de::DeserializeOwned;
use serde_json::Value;
use spline_core::{Error, ErrorKind, Result};

/// What kind of JSON value this is, for messages.
pub(super) fn json_kind(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Deserialises a JSON value into a record; the message names the field
/// (`malformed curve: field control_points[0]: …`).
pub(super) fn deserialize<R: DeserializeOwned>(what: &str, value: Value) -> Result<R> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        let what_went_wrong = serde_message(&e.inner().to_string());
        let message = if path == "." {
            format!("malformed {what}: {what_went_wrong}")
        } else {
            format!("malformed {what}: field {path}: {what_went_wrong}")
        };
        Error::new(ErrorKind::Parse, message)
    })
}

/// serde's words for JSON people: "expected an array, got the number 0" rather than
/// "invalid type: floating point `0`, expected a sequence", and no line and column for
/// one-line values.
///
/// ```
/// use spline_io::exchange::serde_message;
/// assert_eq!(
///     serde_message("invalid type: floating point `0`, expected a sequence at line 1 column 1"),
///     "expected an array, got the number 0"
/// );
/// ```
#[must_use]
pub fn serde_message(message: &str) -> String {
    let mut m = message.to_string();
    if let Some(at) = m.find(" at line 1 column") {
        m.truncate(at);
    }
    let words = |text: &str| {
        text.replace("a sequence", "an array")
            .replace("sequence", "array")
            .replace("a map", "an object")
            .replace("usize", "a non-negative integer")
            .replace("u64", "a non-negative integer")
            .replace("f64", "a number")
            .replace("floating point `", "the number `")
            .replace("integer `", "the number `")
            .replace('`', "")
    };
    for prefix in ["invalid type: ", "invalid value: "] {
        if let Some(rest) = m.strip_prefix(prefix) {
            if let Some((got, expected)) = rest.split_once(", expected ") {
                let got = match got {
                    "map" => "an object".to_string(),
                    "sequence" => "an array".to_string(),
                    "null" => "null".to_string(),
                    other if other.starts_with("string ") || other.starts_with("boolean ") => {
                        format!("the {}", words(other))
                    }
                    other => words(other),
                };
                return format!("expected {}, got {got}", words(expected));
            }
        }
    }
    words(&m)
}
