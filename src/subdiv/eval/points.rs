//! The points file of `subdiv eval`: one point per line, `f u v` (Loop:
//! control triangle `f`, 0-based in the file's face order, and the
//! barycentric `(u, v)`: the point `(1 - u - v) c0 + u c1 + v c2`;
//! Catmull-Clark: ptex face `f` and `(u, v)` in its unit square, see
//! [`super::catmark`]); blank lines and lines starting with `#` are skipped.

use crate::{Error, Result};

/// Slack on `u + v <= 1` for parameters written in decimal.
pub const EDGE_SLACK: f64 = 1e-6;

/// Where a point's `(f, u, v)` lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// This many control triangles, `u, v >= 0`, `u + v <= 1`.
    Triangles(usize),
    /// This many ptex faces, `(u, v)` in the unit square.
    Ptex(usize),
}

#[cfg(test)]
/// Parses and checks a points file `text` (named `file` in messages) for
/// a mesh of `faces` control triangles, reading at most `max_points`.
///
/// # Errors
/// [`Error::Parse`] naming the line: not three fields, a face that is not
/// a non-negative integer or out of range, `u` or `v` not a number,
/// negative, NaN or infinite, `u + v > 1 + 1e-6`, or too many points.
pub(crate) fn parse_points(text: &str, file: &str, faces: usize, max_points: usize) -> Result<Vec<(usize, f64, f64)>> {
    parse_points_in(text, file, Domain::Triangles(faces), max_points)
}

/// `parse_points` in `domain`: for ptex faces, `u` or `v` over `1 +
/// 1e-6` is refused instead of `u + v`.
///
/// # Errors
/// As `parse_points`.
pub fn parse_points_in(text: &str, file: &str, domain: Domain, max_points: usize) -> Result<Vec<(usize, f64, f64)>> {
    // pieces of about 1 MB parsed in parallel; a file with a bad line (or
    // too many points) is parsed again line by line, to name the first
    if let Some(points) = parse_pieces(text, domain, max_points, (1 << 20, 16)) {
        return Ok(points);
    }
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let err = |msg: String| Error::Parse { file: file.to_string(), line: i + 1, msg };
        if !blank(line) && out.len() == max_points {
            return Err(err(format!("more than {max_points} points (raise --limit vertices=N)")));
        }
        out.extend(point(line, domain).map_err(err)?);
    }
    Ok(out)
}

/// The points of `text` parsed in pieces of about `piece` bytes in
/// parallel, or `None` if a line is refused or there are more than
/// `max_points`. The pieces go in batches of `batch`, the count checked
/// after each, so no more than a batch's points are parsed past
/// `max_points`.
fn parse_pieces(
    text: &str,
    domain: Domain,
    max_points: usize,
    (piece, batch): (usize, usize),
) -> Option<Vec<(usize, f64, f64)>> {
    use rayon::prelude::*;
    let mut pieces = Vec::with_capacity(text.len() / piece + 1);
    let mut rest = text;
    while !rest.is_empty() {
        // up to the end of the line that crosses `piece` bytes
        let end = rest.as_bytes().iter().skip(piece).position(|&b| b == b'\n').map_or(rest.len(), |k| piece + k + 1);
        let (first, tail) = rest.split_at(end);
        pieces.push(first);
        rest = tail;
    }
    let mut out = Vec::new();
    for batch in pieces.chunks(batch.max(1)) {
        let parsed: Vec<Vec<(usize, f64, f64)>> = batch
            .par_iter()
            .map(|piece| {
                let mut out = Vec::with_capacity(piece.len() / 24);
                for line in piece.lines() {
                    out.extend(point(line, domain).ok()?);
                }
                Some(out)
            })
            .collect::<Option<_>>()?;
        for points in parsed {
            if out.len() + points.len() > max_points {
                return None;
            }
            out.extend_from_slice(&points);
        }
    }
    Some(out)
}

/// Whether `line` holds no point: blank, or a `#` comment.
fn blank(line: &str) -> bool {
    let line = line.trim_start();
    line.is_empty() || line.starts_with('#')
}

/// One line of a points file: `None` for a blank or `#` line, or why it is
/// refused.
fn point(line: &str, domain: Domain) -> std::result::Result<Option<(usize, f64, f64)>, String> {
    let (faces, what) = match domain {
        Domain::Triangles(n) => (n, "triangles"),
        Domain::Ptex(n) => (n, "ptex faces"),
    };
    if blank(line) {
        return Ok(None);
    }
    let mut fields = line.split_whitespace();
    let (Some(f), Some(u), Some(v), None) = (fields.next(), fields.next(), fields.next(), fields.next()) else {
        return Err(format!("expected 'f u v', found {} fields", line.split_whitespace().count()));
    };
    let f: usize = f.parse().map_err(|_| format!("face '{f}' is not a non-negative integer"))?;
    if f >= faces {
        return Err(format!("face {f} out of range (the mesh has {faces} {what})"));
    }
    let num = |s: &str, name: &str| -> std::result::Result<f64, String> {
        let x: f64 = s.parse().map_err(|_| format!("{name} '{s}' is not a number"))?;
        if !x.is_finite() || x < 0.0 {
            return Err(format!("{name} = {x}: must be finite and >= 0"));
        }
        Ok(x)
    };
    let (u, v) = (num(u, "u")?, num(v, "v")?);
    match domain {
        Domain::Triangles(_) if u + v > 1.0 + EDGE_SLACK => {
            Err(format!("u + v = {} > 1: the point is outside the triangle", u + v))
        }
        Domain::Ptex(_) if u.max(v) > 1.0 + EDGE_SLACK => Err(format!("({u}, {v}) is outside the unit square")),
        _ => Ok(Some((f, u, v))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn good_points_parse_and_bad_ones_name_their_line() {
        let ok = parse_points("# f u v\n0 0.25 0.5\n\n3 0 1e-3\n", "p.txt", 4, 10).unwrap();
        assert_eq!(ok, vec![(0, 0.25, 0.5), (3, 0.0, 1e-3)]);
        for (text, line, what) in [
            ("0 0.1 0.1\n4 0.1 0.1", 2, "out of range"),
            ("-1 0.1 0.1", 1, "non-negative"),
            ("0 -0.1 0.1", 1, "u = -0.1"),
            ("0 NaN 0.1", 1, "u = NaN"),
            ("0 0.1 inf", 1, "v = inf"),
            ("0 0.6 0.6", 1, "outside"),
            ("0 0.1", 1, "2 fields"),
            ("0 a 0.1", 1, "'a' is not a number"),
        ] {
            let e = parse_points(text, "p.txt", 4, 10).unwrap_err().to_string();
            assert!(e.starts_with(&format!("p.txt:{line}: ")) && e.contains(what), "{text}: {e}");
        }
        assert!(parse_points("0 0.5 0.500000001", "p.txt", 4, 10).is_ok());
        assert!(parse_points("0 0 0\n0 0 0", "p.txt", 4, 1).unwrap_err().to_string().contains("more than 1"));
    }

    #[test]
    fn a_file_of_many_pieces_parses_as_line_by_line_and_names_a_late_bad_line() {
        // about 3 MB: several pieces parsed in parallel, a comment, a blank
        // line and a CRLF line among them
        let mut text = String::from("# f u v\n\n");
        let mut want = Vec::new();
        for i in 0..200_000usize {
            let (f, u, v) = (i % 97, (i % 1000) as f64 / 2000.0, (i % 7) as f64 / 16.0);
            text.push_str(&format!("{f} {u:?} {v:?}{}", if i % 10_000 == 5 { "\r\n" } else { "\n" }));
            want.push((f, u, v));
        }
        assert!(text.len() > 2 << 20, "{}", text.len());
        assert_eq!(parse_points(&text, "p.txt", 97, usize::MAX).unwrap(), want);
        // the point count is checked over all the pieces
        let e = parse_points(&text, "p.txt", 97, want.len() - 1).unwrap_err().to_string();
        assert!(e.starts_with(&format!("p.txt:{}: more than", want.len() + 2)), "{e}");
        // a bad line in the last piece is named by its line in the file
        let bad = format!("{text}5 0.1 0.1\n97 0.1 0.1\n");
        let e = parse_points(&bad, "p.txt", 97, usize::MAX).unwrap_err().to_string();
        assert!(e.starts_with(&format!("p.txt:{}: face 97 out of range", want.len() + 4)), "{e}");
        // small pieces in small batches: lines cut nowhere, the count
        // stopped at the batch that passes it
        let small = (40, 3);
        let text: String = want[..500].iter().map(|(f, u, v)| format!("{f} {u:?} {v:?}\n")).collect();
        assert_eq!(parse_pieces(&text, Domain::Triangles(97), 500, small).as_deref(), Some(&want[..500]));
        assert!(parse_pieces(&text, Domain::Triangles(97), 499, small).is_none());
        assert!(parse_pieces(&format!("{text}x"), Domain::Triangles(97), 600, small).is_none());
    }
}
