//! Polylines in the parameter domain of a surface, and their joining end to end (the zero
//! sets and the ridges are found as pieces, box by box).

/// Points of a polyline in the parameter domain.
pub type UvPolyline = Vec<[f64; 2]>;

/// Joins `next` to `line` at the end where they meet (the end of `line` first, then its
/// start), turned round where needed; the shared point kept once.
fn attach(
    line: &mut UvPolyline,
    mut next: UvPolyline,
    near: impl Fn(&[f64; 2], &[f64; 2]) -> bool,
) {
    let (start, end) = (line[0], line[line.len() - 1]);
    let last = next[next.len() - 1];
    if near(&next[0], &end) {
        line.extend(next.drain(1..));
    } else if near(&last, &end) {
        next.reverse();
        line.extend(next.drain(1..));
    } else {
        if !near(&last, &start) {
            next.reverse();
        }
        next.pop();
        next.append(line);
        *line = next;
    }
}

/// Joins pieces whose ends meet (within `tol`) into polylines; a polyline whose ends meet is
/// closed (its first point repeated at the end). Each line grows by the first remaining
/// piece (in list order) with an end near one of its ends, found through [`Ends`], so
/// that joining `n` pieces takes `O(n)` lookups instead of `O(n²)` comparisons.
pub(crate) fn chain(mut pieces: Vec<UvPolyline>, tol: f64) -> Vec<UvPolyline> {
    let near =
        |a: &[f64; 2], b: &[f64; 2]| (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol;
    pieces.retain(|p| p.len() >= 2);
    let mut ends = Ends::new(tol);
    for (k, p) in pieces.iter().enumerate() {
        ends.add(p, k);
    }
    let mut out = Vec::new();
    while let Some(mut line) = pieces.pop() {
        ends.remove(&line, pieces.len());
        loop {
            let end = *line.last().expect("non-empty");
            let start = line[0];
            if line.len() > 2 && near(&start, &end) {
                break;
            }
            let Some(k) = ends
                .around(&end)
                .chain(ends.around(&start))
                .filter(|&k| {
                    let p = &pieces[k];
                    near(&p[0], &end)
                        || near(p.last().expect("non-empty"), &end)
                        || near(&p[0], &start)
                        || near(p.last().expect("non-empty"), &start)
                })
                .min()
            else {
                break;
            };
            // `swap_remove` moves the last piece into slot `k`: its ends follow it.
            let last = pieces.len() - 1;
            ends.remove(&pieces[k], k);
            if k != last {
                ends.remove(&pieces[last], last);
                ends.add(&pieces[last], k);
            }
            attach(&mut line, pieces.swap_remove(k), near);
        }
        out.push(line);
    }
    out
}

/// The ends of the pieces [`chain`] has left, by square cell of side `2·tol`: a point within
/// `tol` of an end (in each coordinate) lies in one of the nine cells around that end's.
struct Ends {
    side: f64,
    cells: std::collections::HashMap<(i64, i64), Vec<usize>>,
}

impl Ends {
    fn new(tol: f64) -> Self {
        let side = 2.0 * tol;
        Self {
            // Any positive side finds equal points when `tol` is 0.
            side: if side > 0.0 && side.is_finite() {
                side
            } else {
                1.0
            },
            cells: std::collections::HashMap::new(),
        }
    }

    fn cell(&self, p: &[f64; 2]) -> (i64, i64) {
        // `as` saturates (and maps NaN to 0): far or invalid points share cells, which only
        // adds candidates, never loses one.
        (
            (p[0] / self.side).floor() as i64,
            (p[1] / self.side).floor() as i64,
        )
    }

    fn add(&mut self, piece: &[[f64; 2]], k: usize) {
        for p in [&piece[0], &piece[piece.len() - 1]] {
            let cell = self.cell(p);
            self.cells.entry(cell).or_default().push(k);
        }
    }

    fn remove(&mut self, piece: &[[f64; 2]], k: usize) {
        for p in [&piece[0], &piece[piece.len() - 1]] {
            let cell = self.cell(p);
            if let Some(list) = self.cells.get_mut(&cell) {
                if let Some(at) = list.iter().position(|&x| x == k) {
                    list.swap_remove(at);
                }
            }
        }
    }

    /// The pieces with an end in the nine cells around `p`'s (some twice).
    fn around(&self, p: &[f64; 2]) -> impl Iterator<Item = usize> + '_ {
        let (i, j) = self.cell(p);
        (-1i64..=1).flat_map(move |di| {
            (-1i64..=1).flat_map(move |dj| {
                self.cells
                    .get(&(i.saturating_add(di), j.saturating_add(dj)))
                    .into_iter()
                    .flatten()
                    .copied()
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{UvPolyline, attach, chain};

    /// The joining by linear search over every remaining piece (the definition [`chain`]'s
    /// index must reproduce, piece for piece and in the same order).
    fn chain_by_search(mut pieces: Vec<UvPolyline>, tol: f64) -> Vec<UvPolyline> {
        let near =
            |a: &[f64; 2], b: &[f64; 2]| (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol;
        pieces.retain(|p| p.len() >= 2);
        let mut out = Vec::new();
        while let Some(mut line) = pieces.pop() {
            loop {
                let (start, end) = (line[0], line[line.len() - 1]);
                if line.len() > 2 && near(&start, &end) {
                    break;
                }
                let Some(k) = pieces.iter().position(|p| {
                    let last = &p[p.len() - 1];
                    near(&p[0], &end)
                        || near(last, &end)
                        || near(&p[0], &start)
                        || near(last, &start)
                }) else {
                    break;
                };
                attach(&mut line, pieces.swap_remove(k), near);
            }
            out.push(line);
        }
        out
    }

    /// Segments between the nodes of a coarse grid (so that many ends meet, in branching
    /// ways), each end moved by up to twice the tolerance (so that some meet and some do
    /// not), in a shuffled order: the indexed joining equals the linear search exactly.
    #[test]
    fn chain_equals_the_linear_search() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for (case, tol) in [1e-9, 1e-3, 0.0, 0.05].into_iter().enumerate() {
            let mut pieces = Vec::new();
            for _ in 0..400 + 100 * case {
                let node = |next: &mut dyn FnMut() -> f64| {
                    let (i, j) = ((next() * 12.0).floor(), (next() * 12.0).floor());
                    let jitter = if next() < 0.5 {
                        2.0 * tol * (next() - 0.5) * 2.0
                    } else {
                        0.0
                    };
                    [i / 12.0 + jitter, j / 12.0]
                };
                let a = node(&mut next);
                let b = node(&mut next);
                let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]) + 0.01 * next()];
                pieces.push(if next() < 0.3 {
                    vec![a, mid, b]
                } else {
                    vec![a, b]
                });
            }
            pieces.push(vec![[0.5, 0.5]]);
            assert_eq!(
                chain(pieces.clone(), tol),
                chain_by_search(pieces, tol),
                "tol {tol}"
            );
        }
    }
}
