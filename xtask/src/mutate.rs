//! Deterministic structured mutations shared by `cargo xtask fuzz` (in process) and
//! `cargo xtask campaign` (subprocess runs of the tool): a small seeded generator, extreme
//! numbers, and mutations of JSON values, text and command-line values.

use serde_json::{Value, json};

/// SplitMix64: a small, fast, well-distributed generator; the same seed gives the same cases
/// on every machine.
///
/// [`Rng::from_bytes`] draws from a tape of bytes first (8 bytes a number) and from the
/// generator once the tape runs out: the coverage-guided fuzzer (`fuzz/`, libFuzzer) then
/// steers every decision of a case by mutating the bytes it hands in.
#[derive(Clone, Debug)]
pub(crate) struct Rng {
    state: u64,
    tape: Vec<u8>,
    position: usize,
}

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self {
            state: seed ^ 0x9E37_79B9_7F4A_7C15,
            tape: Vec::new(),
            position: 0,
        }
    }

    /// A generator that replays `bytes` (little-endian numbers) before it generates; its
    /// seed is a hash of the bytes, so that equal inputs give equal cases.
    pub(crate) fn from_bytes(bytes: &[u8]) -> Self {
        let hash = bytes.iter().fold(0xCBF2_9CE4_8422_2325_u64, |h, &b| {
            (h ^ u64::from(b)).wrapping_mul(0x100_0000_01B3)
        });
        Self {
            tape: bytes.to_vec(),
            ..Self::new(hash)
        }
    }

    pub(crate) fn next_u64(&mut self) -> u64 {
        if let Some(chunk) = self.tape.get(self.position..self.position + 8) {
            self.position += 8;
            let mut word = [0u8; 8];
            word.copy_from_slice(chunk);
            return u64::from_le_bytes(word);
        }
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (`n > 0`).
    pub(crate) fn below(&mut self, n: usize) -> usize {
        // n is small: the modulo bias is irrelevant here.
        #[allow(clippy::cast_possible_truncation)]
        let r = (self.next_u64() % n.max(1) as u64) as usize;
        r
    }

    /// A uniform number in `[0, 1)`.
    pub(crate) fn unit(&mut self) -> f64 {
        #[allow(clippy::cast_precision_loss)]
        let r = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        r
    }

    pub(crate) fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    pub(crate) fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Counts and numbers at the edges: the values that broke the tool before.
pub(crate) const EXTREME_TEXT: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "7",
    "33",
    "1000",
    "100000",
    "1000000000",
    "4294967296",
    "9223372036854775807",
    "18446744073709551615",
    "18446744073709551616",
    "-1",
    "-0",
    "0.5",
    "1e-300",
    "1e300",
    "5e-324",
    "-5e-324",
    "1e-19",
    "1e308",
    "1e155",
    "1e-9",
    "1e9",
    "NaN",
    "inf",
    "-inf",
    "abc",
    "",
];

/// Extreme JSON numbers.
pub(crate) const EXTREME_NUMBERS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e-300,
    1e300,
    5e-324,
    -5e-324,
    1e308,
    -1e308,
    1e155,
    1e-155,
    1e9,
    1e-9,
    1_000_000_000_000.094_1,
    0.105_453_239_336_108_95,
    9.223_372_036_854_776e18,
    1.844_674_407_370_955_2e19,
    33.0,
    1000.0,
];

/// One mutation of a JSON value, at a random node.
pub(crate) fn mutate_value(rng: &mut Rng, value: &mut Value) {
    match rng.below(12) {
        0 => scale_numbers(
            value,
            *rng.pick(&[1e150, 1e-150, 1e80, 1e-100, 1e300, 1e-300]),
        ),
        1 => {
            let n = count_numbers(value);
            if n > 0 {
                let target = rng.below(n);
                let x = *rng.pick(EXTREME_NUMBERS);
                set_number(value, target, &mut 0, x);
            }
        }
        _ => {
            let nodes = count_nodes(value);
            let target = rng.below(nodes);
            let mut seen = 0;
            mutate_node(rng, value, target, &mut seen);
        }
    }
}

fn mutate_node(rng: &mut Rng, value: &mut Value, target: usize, seen: &mut usize) -> bool {
    if *seen == target {
        *value = mutated_node(rng, value);
        return true;
    }
    *seen += 1;
    match value {
        Value::Array(items) => items.iter_mut().any(|v| mutate_node(rng, v, target, seen)),
        Value::Object(map) => map.values_mut().any(|v| mutate_node(rng, v, target, seen)),
        _ => false,
    }
}

fn mutated_node(rng: &mut Rng, value: &Value) -> Value {
    match rng.below(10) {
        0 => Value::Null,
        1 => json!("x"),
        2 => json!({}),
        3 => json!([]),
        4 => json!([value.clone()]),
        5 => match value {
            Value::Array(items) if !items.is_empty() => {
                let mut items = items.clone();
                items.remove(rng.below(items.len()));
                Value::Array(items)
            }
            _ => json!(rng.pick(EXTREME_NUMBERS)),
        },
        6 => match value {
            Value::Array(items) if !items.is_empty() => {
                let mut items = items.clone();
                let k = rng.below(items.len());
                let copies = *rng.pick(&[1usize, 2, 10, 1000]);
                for _ in 0..copies {
                    items.insert(k, items[k].clone());
                }
                Value::Array(items)
            }
            _ => json!(rng.pick(EXTREME_NUMBERS)),
        },
        7 => match value {
            Value::Array(items) if items.len() > 1 => {
                let mut items = items.clone();
                items.reverse();
                Value::Array(items)
            }
            _ => json!(-1),
        },
        _ => json!(rng.pick(EXTREME_NUMBERS)),
    }
}

fn count_nodes(value: &Value) -> usize {
    1 + match value {
        Value::Array(items) => items.iter().map(count_nodes).sum(),
        Value::Object(map) => map.values().map(count_nodes).sum(),
        _ => 0,
    }
}

fn count_numbers(value: &Value) -> usize {
    match value {
        Value::Number(_) => 1,
        Value::Array(items) => items.iter().map(count_numbers).sum(),
        Value::Object(map) => map.values().map(count_numbers).sum(),
        _ => 0,
    }
}

fn set_number(value: &mut Value, target: usize, seen: &mut usize, x: f64) -> bool {
    match value {
        Value::Number(_) => {
            let hit = *seen == target;
            *seen += 1;
            if hit {
                *value = json!(x);
            }
            hit
        }
        Value::Array(items) => items.iter_mut().any(|v| set_number(v, target, seen, x)),
        Value::Object(map) => map
            .iter_mut()
            // Scaling degrees makes no sense; everything else is fair game.
            .any(|(_, v)| set_number(v, target, seen, x)),
        _ => false,
    }
}

/// Multiplies every floating-point number (not the integer degrees) by `factor`.
pub(crate) fn scale_numbers(value: &mut Value, factor: f64) {
    match value {
        Value::Number(n) if n.is_f64() => {
            if let Some(x) = n.as_f64() {
                let y = x * factor;
                if y.is_finite() {
                    *value = json!(y);
                }
            }
        }
        Value::Array(items) => items.iter_mut().for_each(|v| scale_numbers(v, factor)),
        Value::Object(map) => {
            for (key, v) in map.iter_mut() {
                if key != "degree" && key != "knots" && key != "weights" {
                    scale_numbers(v, factor);
                }
            }
        }
        _ => {}
    }
}

/// One mutation of text: a flipped byte, a cut, deep nesting, garbage, or nothing at all.
pub(crate) fn mutate_text(rng: &mut Rng, text: &str) -> String {
    let mut bytes = text.as_bytes().to_vec();
    match rng.below(6) {
        0 if !bytes.is_empty() => {
            let k = rng.below(bytes.len());
            bytes[k] = *rng.pick(b"[]{},:\"0.-e9 \n\x00\xff#x");
        }
        1 if !bytes.is_empty() => bytes.truncate(rng.below(bytes.len())),
        2 => {
            let depth = *rng.pick(&[10usize, 200, 100_000]);
            let mut nested = "[".repeat(depth).into_bytes();
            nested.extend(std::iter::repeat_n(b']', depth));
            bytes = nested;
        }
        3 => {
            bytes = (0..rng.below(200))
                .map(|_| rng.next_u64().to_le_bytes()[0])
                .collect();
        }
        4 => bytes.clear(),
        _ => {
            let k = rng.below(bytes.len() + 1);
            bytes.splice(k..k, b"1e400".iter().copied());
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

/// A mutated command-line value: an extreme number, a mutated JSON value, or mutated text.
pub(crate) fn mutate_arg(rng: &mut Rng, arg: &str) -> String {
    match serde_json::from_str::<Value>(arg) {
        Ok(mut value) if value.is_array() && rng.chance(0.7) => {
            mutate_value(rng, &mut value);
            return value.to_string();
        }
        _ => {}
    }
    if arg.parse::<f64>().is_ok() && rng.chance(0.6) {
        // A number stays a number: counts and values at the edges.
        (*rng.pick(&EXTREME_TEXT[..26])).to_string()
    } else if rng.chance(0.75) {
        (*rng.pick(EXTREME_TEXT)).to_string()
    } else {
        // A command-line value is at most 128 KiB (MAX_ARG_STRLEN).
        // and cannot hold a NUL byte.
        mutate_text(rng, arg)
            .chars()
            .filter(|&c| c != '\0')
            .take(100_000)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generator_is_deterministic() {
        let mut a = Rng::new(7);
        let mut b = Rng::new(7);
        let xs: Vec<u64> = (0..5).map(|_| a.next_u64()).collect();
        let ys: Vec<u64> = (0..5).map(|_| b.next_u64()).collect();
        assert_eq!(xs, ys);
        assert_ne!(xs[0], xs[1]);
    }

    #[test]
    fn a_tape_is_replayed_then_the_generator_takes_over() {
        let mut bytes = 7u64.to_le_bytes().to_vec();
        bytes.extend_from_slice(&[1, 2, 3]);
        let mut a = Rng::from_bytes(&bytes);
        assert_eq!(a.next_u64(), 7);
        let mut b = Rng::from_bytes(&bytes);
        b.next_u64();
        assert_eq!(a.next_u64(), b.next_u64());
        assert_ne!(
            Rng::from_bytes(&[1]).next_u64(),
            Rng::from_bytes(&[2]).next_u64()
        );
    }

    #[test]
    fn scaling_keeps_degrees_and_knots() {
        let mut v =
            json!({"degree": 1, "knots": [0.0, 0.0, 1.0, 1.0], "control_points": [[0.5, 1.0]]});
        scale_numbers(&mut v, 1e150);
        assert_eq!(v["knots"], json!([0.0, 0.0, 1.0, 1.0]));
        assert_eq!(v["control_points"], json!([[0.5e150, 1e150]]));
        assert_eq!(v["degree"], json!(1));
    }
}
