//! Points grouped by face for a batch evaluation: a counting sort whose
//! passes run in parallel. The histogram is summed over chunks of points;
//! the scatter is split by ranges of faces of about equal point counts,
//! each range a disjoint piece of the output that one task fills in one
//! scan of all the points; the rank of each point is written once, by the
//! task that owns its face.

use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Points grouped by face: `sorted[rank[i]]` is point `i` (its face and
/// `(u, v)` as the caller mapped them), the points of each face in input
/// order.
pub(super) struct Grouped {
    pub(super) sorted: Vec<(usize, (f64, f64))>,
    pub(super) rank: Vec<AtomicUsize>,
}

/// Points per chunk of the histogram.
const CHUNK: usize = 1 << 16;

/// `start[f]`: where face `f`'s points begin in the grouped order (`faces
/// + 1` entries, the last the number of points), or the index of the first
/// point that `fits` refuses.
fn starts(
    points: &[(usize, f64, f64)],
    faces: usize,
    fits: impl Fn(&(usize, f64, f64)) -> bool + Sync,
) -> Result<Vec<usize>, usize> {
    let counts = points
        .par_chunks(CHUNK)
        .enumerate()
        .fold(
            || (vec![0usize; faces + 1], None),
            |(mut c, bad): (Vec<usize>, Option<usize>), (k, chunk)| {
                if bad.is_some() {
                    return (c, bad);
                }
                for (j, p) in chunk.iter().enumerate() {
                    if !fits(p) {
                        return (c, Some(k * CHUNK + j));
                    }
                    c[p.0 + 1] += 1;
                }
                (c, bad)
            },
        )
        .reduce_with(|(mut a, bad_a), (b, bad_b)| {
            a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
            (a, bad_a.into_iter().chain(bad_b).min())
        });
    let (mut start, bad) = counts.unwrap_or_else(|| (vec![0; faces + 1], None));
    if let Some(i) = bad {
        return Err(i);
    }
    for k in 1..start.len() {
        start[k] += start[k - 1];
    }
    Ok(start)
}

/// `points` grouped by face, each `(u, v)` mapped by `onto`, or the index
/// of the first point that `fits` refuses (a point it passes has its face
/// below `faces`).
pub(super) fn by_face(
    points: &[(usize, f64, f64)],
    faces: usize,
    fits: impl Fn(&(usize, f64, f64)) -> bool + Sync,
    onto: impl Fn(f64, f64) -> (f64, f64) + Sync,
) -> Result<Grouped, usize> {
    let n = points.len();
    let start = starts(points, faces, fits)?;
    // face ranges of about n / parts points each: bounds[k]..bounds[k + 1]
    let parts = rayon::current_num_threads().clamp(1, 64);
    let bounds: Vec<usize> = (0..=parts).map(|k| start.partition_point(|&x| x < n * k / parts).min(faces)).collect();
    let mut sorted = vec![(0, (0.0, 0.0)); n];
    let rank: Vec<AtomicUsize> = (0..n).map(|_| AtomicUsize::new(0)).collect();
    let mut pieces = Vec::with_capacity(parts);
    let mut rest = &mut sorted[..];
    for w in bounds.windows(2) {
        let (piece, tail) = rest.split_at_mut(start[w[1]] - start[w[0]]);
        pieces.push((w[0]..w[1], piece));
        rest = tail;
    }
    pieces.into_par_iter().for_each(|(range, piece)| {
        let base = start[range.start];
        let mut next: Vec<usize> = start[range.clone()].iter().map(|&x| x - base).collect();
        for (i, &(f, u, v)) in points.iter().enumerate() {
            if range.contains(&f) {
                let r = &mut next[f - range.start];
                piece[*r] = (f, onto(u, v));
                rank[i].store(base + *r, Ordering::Relaxed);
                *r += 1;
            }
        }
    });
    Ok(Grouped { sorted, rank })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_are_grouped_by_face_in_input_order_and_ranked() {
        // faces with no point, one point and many; several chunks of the
        // histogram; on one thread and on four (several face ranges)
        let faces = 1000;
        let points: Vec<(usize, f64, f64)> =
            (0..3 * CHUNK).map(|i| ((i * 7919) % 997 + (i % 3) * (i % 5 == 0) as usize, i as f64, 0.5)).collect();
        for threads in [1, 4] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("a pool");
            let g = pool.install(|| by_face(&points, faces, |_| true, |u, v| (v, u))).expect("all fit");
            let mut want: Vec<usize> = (0..points.len()).collect();
            want.sort_by_key(|&i| points[i].0);
            let rank: Vec<usize> = g.rank.iter().map(|r| r.load(Ordering::Relaxed)).collect();
            for (j, &i) in want.iter().enumerate() {
                assert_eq!(rank[i], j, "{threads} threads: point {i}");
                assert_eq!(g.sorted[j], (points[i].0, (0.5, i as f64)), "{threads} threads: place {j}");
            }
            // the first refused point, wherever the chunks end
            for bad in [0, CHUNK - 1, CHUNK, 2 * CHUNK + 5] {
                let refused = pool
                    .install(|| by_face(&points, faces, |p| p.1 < bad as f64 || p.1 > (bad + 3) as f64, |u, v| (u, v)));
                assert_eq!(refused.err(), Some(bad), "{threads} threads");
            }
        }
    }
}
