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

/// Parses and checks a points file `text` (named `file` in messages) for
/// a mesh of `faces` control triangles, reading at most `max_points`.
///
/// # Errors
/// [`Error::Parse`] naming the line: not three fields, a face that is not
/// a non-negative integer or out of range, `u` or `v` not a number,
/// negative, NaN or infinite, `u + v > 1 + 1e-6`, or too many points.
pub fn parse_points(text: &str, file: &str, faces: usize, max_points: usize) -> Result<Vec<(usize, f64, f64)>> {
    parse_points_in(text, file, Domain::Triangles(faces), max_points)
}

/// [`parse_points`] in `domain`: for ptex faces, `u` or `v` over `1 +
/// 1e-6` is refused instead of `u + v`.
///
/// # Errors
/// As [`parse_points`].
pub fn parse_points_in(text: &str, file: &str, domain: Domain, max_points: usize) -> Result<Vec<(usize, f64, f64)>> {
    let (faces, what) = match domain {
        Domain::Triangles(n) => (n, "triangles"),
        Domain::Ptex(n) => (n, "ptex faces"),
    };
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let err = |msg: String| Error::Parse { file: file.to_string(), line: i + 1, msg };
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if out.len() == max_points {
            return Err(err(format!("more than {max_points} points (raise --limit vertices=N)")));
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let [f, u, v] = fields[..] else {
            return Err(err(format!("expected 'f u v', found {} fields", fields.len())));
        };
        let f: usize = f.parse().map_err(|_| err(format!("face '{f}' is not a non-negative integer")))?;
        if f >= faces {
            return Err(err(format!("face {f} out of range (the mesh has {faces} {what})")));
        }
        let num = |s: &str, name: &str| -> Result<f64> {
            let x: f64 = s.parse().map_err(|_| err(format!("{name} '{s}' is not a number")))?;
            if !x.is_finite() || x < 0.0 {
                return Err(err(format!("{name} = {x}: must be finite and >= 0")));
            }
            Ok(x)
        };
        let (u, v) = (num(u, "u")?, num(v, "v")?);
        match domain {
            Domain::Triangles(_) if u + v > 1.0 + EDGE_SLACK => {
                return Err(err(format!("u + v = {} > 1: the point is outside the triangle", u + v)));
            }
            Domain::Ptex(_) if u.max(v) > 1.0 + EDGE_SLACK => {
                return Err(err(format!("({u}, {v}) is outside the unit square")));
            }
            _ => {}
        }
        out.push((f, u, v));
    }
    Ok(out)
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
}
