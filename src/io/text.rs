//! Text put together line by line for the writers of large text files
//! (OBJ, OFF, `.ct`): numbers are formatted into a small array with copies
//! of sizes fixed at compile time, and the array is appended whole.

/// One line of text being put together. Every copy into it and out of it
/// has a size fixed at compile time, which the compiler turns into a few
/// moves; appending each number to the output as it comes costs a
/// `memmove` call per number, more than formatting the digits.
///
/// `CAP` is the room: the longest line and its prefix (at most 2 bytes).
pub(crate) struct Line<const CAP: usize = 64> {
    bytes: [u8; CAP],
    /// Length of the prefix every line starts with.
    start: usize,
    /// Bytes of the line so far.
    at: usize,
}

/// The longest line of three floats: a 2-byte prefix and three numbers of
/// at most 16 characters (a shortest round-trip f32) with their separators,
/// longer than any line of three ids (10 digits at most). The default room
/// of a [`Line`] holds it.
pub(crate) const LONGEST: usize = 2 + 3 * 16 + 3;

impl<const CAP: usize> Line<CAP> {
    /// A line that starts with `prefix` (at most 2 bytes) every time.
    pub(crate) fn new(prefix: &[u8]) -> Self {
        let mut bytes = [0u8; CAP];
        bytes[..prefix.len()].copy_from_slice(prefix);
        Line { bytes, start: prefix.len(), at: prefix.len() }
    }

    /// Starts the next line (after the prefix).
    #[inline(always)]
    pub(crate) fn reset(&mut self) {
        self.at = self.start;
    }

    /// Appends one byte.
    #[inline(always)]
    pub(crate) fn push(&mut self, b: u8) {
        self.bytes[self.at] = b;
        self.at += 1;
    }

    /// Appends `s` (a formatted number): two overlapping copies of 8 (or 4)
    /// bytes cover every length from 8 to 16 (4 to 7), as `memcpy` does
    /// inside, without the call.
    #[inline(always)]
    pub(crate) fn put(&mut self, s: &[u8]) {
        let (at, n) = (self.at, s.len());
        match n {
            8..=16 => {
                self.bytes[at..at + 8].copy_from_slice(&s[..8]);
                self.bytes[at + n - 8..at + n].copy_from_slice(&s[n - 8..]);
            }
            4..=7 => {
                self.bytes[at..at + 4].copy_from_slice(&s[..4]);
                self.bytes[at + n - 4..at + n].copy_from_slice(&s[n - 4..]);
            }
            _ => self.bytes[at..at + n].copy_from_slice(s),
        }
        self.at += n;
    }

    /// Appends the decimal digits of `x`.
    #[inline(always)]
    pub(crate) fn put_u32(&mut self, x: u32) {
        self.at = put_u32(&mut self.bytes, self.at, x);
    }

    /// Appends the line alone to `out` (a copy of its length), for a room
    /// much longer than its usual lines.
    #[inline(always)]
    pub(crate) fn append_used_to(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.bytes[..self.at]);
    }

    /// Appends the whole array to `out` (a fixed-size copy) and drops what
    /// lies past the line.
    #[inline(always)]
    pub(crate) fn append_to(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.bytes);
        out.truncate(out.len() - (CAP - self.at));
    }
}

/// One line per triple of ids (V-table rows): `prefix`, then each id as
/// `put` writes it, separated by spaces. The face lines of OBJ (1-based),
/// OFF (`3 a b c`) and the V and O tables of `.ct`.
pub(crate) fn triple_lines(prefix: &[u8], ids: &[u32], put: impl Fn(&mut Line, u32)) -> Vec<u8> {
    let mut out = Vec::with_capacity(ids.len() / 3 * LONGEST + 64);
    let mut line: Line = Line::new(prefix);
    for t in ids.chunks_exact(3) {
        line.reset();
        put(&mut line, t[0]);
        line.push(b' ');
        put(&mut line, t[1]);
        line.push(b' ');
        put(&mut line, t[2]);
        line.push(b'\n');
        line.append_to(&mut out);
    }
    out
}

/// [`triple_lines`] of rows of `k` ids (`k` from 1 to 4: a prefix and five
/// numbers of 10 digits fit a line).
pub(crate) fn row_lines(prefix: &[u8], ids: &[u32], k: usize, put: impl Fn(&mut Line, u32)) -> Vec<u8> {
    if k == 3 {
        return triple_lines(prefix, ids, put);
    }
    let mut out = Vec::with_capacity(ids.len() / k * (LONGEST + 16) + 64);
    let mut line: Line = Line::new(prefix);
    for row in ids.chunks_exact(k) {
        line.reset();
        for (i, &id) in row.iter().enumerate() {
            if i > 0 {
                line.push(b' ');
            }
            put(&mut line, id);
        }
        line.push(b'\n');
        line.append_to(&mut out);
    }
    out
}

/// One line per row of `rows` (at most 10 numbers a row), the numbers
/// separated by spaces, each the shortest decimal that reads back as the
/// same double (zmij; an exponent where that is shorter, as `1e-7`), NaN
/// and the infinities as Rust writes them (`NaN`, `inf`, `-inf`).
pub(crate) fn f64_lines<const N: usize>(rows: &[[f64; N]]) -> Vec<u8> {
    // 24 characters at most a number (-2.2250738585072014e-308) and a space
    const { assert!(N <= 10, "a line holds at most 10 numbers") };
    let mut out = Vec::with_capacity(rows.len() * N * 20);
    let mut rb = zmij::Buffer::new();
    let mut line: Line<256> = Line::new(b"");
    for row in rows {
        line.reset();
        for (k, &x) in row.iter().enumerate() {
            if k > 0 {
                line.push(b' ');
            }
            line.put(rb.format(x).as_bytes());
        }
        line.push(b'\n');
        // a row of six is about 110 bytes of the 256
        line.append_used_to(&mut out);
    }
    out
}

/// Two decimal digits of every number below 100.
const DIGIT_PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819202122232425262728293031323334353637383940414243444546474849\
5051525354555657585960616263646566676869707172737475767778798081828384858687888990919293949596979899";

/// Writes the decimal digits of `x` into `line` from `at`; returns the index
/// after the last digit. `line` must have room for 10 digits from `at`.
#[inline]
fn put_u32<const CAP: usize>(line: &mut [u8; CAP], at: usize, mut x: u32) -> usize {
    let end = at + x.checked_ilog10().map_or(1, |d| d as usize + 1);
    let mut k = end;
    while x >= 100 {
        let r = (x % 100) as usize * 2;
        x /= 100;
        k -= 2;
        line[k..k + 2].copy_from_slice(&DIGIT_PAIRS[r..r + 2]);
    }
    if x >= 10 {
        let r = x as usize * 2;
        line[k - 2..k].copy_from_slice(&DIGIT_PAIRS[r..r + 2]);
    } else {
        line[k - 1] = b'0' + x as u8;
    }
    end
}

/// One line per face of `pt` in `faces`: `prefix`, then (with `count`) the
/// face's size, then each corner's vertex as `put` writes it, separated by
/// spaces. The face lines of OBJ (1-based) and OFF for polygon meshes.
pub(crate) fn face_lines(
    prefix: &[u8],
    pt: &crate::mesh::poly::PolyTable,
    faces: std::ops::Range<u32>,
    count: bool,
    put: impl Fn(&mut Line, u32),
) -> Vec<u8> {
    let mut out = Vec::with_capacity(faces.len() * (LONGEST + 16) + 64);
    let mut line: Line = Line::new(prefix);
    let mut long = itoa::Buffer::new();
    for f in faces {
        let r = pt.face_corners(f);
        let k = r.end - r.start;
        if k <= 4 {
            // a prefix and up to five numbers of 10 digits fit the line
            line.reset();
            if count {
                line.put_u32(k);
                line.push(b' ');
            }
            for (i, c) in r.enumerate() {
                if i > 0 {
                    line.push(b' ');
                }
                put(&mut line, pt.vtx(c));
            }
            line.push(b'\n');
            line.append_to(&mut out);
        } else {
            // a long polygon: one number at a time
            out.extend_from_slice(prefix);
            if count {
                out.extend_from_slice(long.format(k).as_bytes());
                out.push(b' ');
            }
            for (i, c) in r.enumerate() {
                if i > 0 {
                    out.push(b' ');
                }
                let mut one: Line<16> = Line::new(b"");
                put_into(&mut one, &put, pt.vtx(c));
                one.append_to(&mut out);
            }
            out.push(b'\n');
        }
    }
    out
}

/// `put` of the default line into a shorter one (one number).
fn put_into(one: &mut Line<16>, put: &impl Fn(&mut Line, u32), x: u32) {
    let mut wide: Line = Line::new(b"");
    put(&mut wide, x);
    one.put(&wide.bytes[..wide.at]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_of_doubles_read_back_bit_for_bit() {
        let odd =
            [0.0, -0.0, 1.0, -2.5, 1e-7, 5.697280448680703e-6, 0.1, 1.0 / 3.0, 1e22, f64::MAX, -f64::MIN_POSITIVE];
        let mut rows: Vec<[f64; 8]> = odd.iter().map(|&x| [x; 8]).collect();
        rows.push([f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 5e-324, 0.5, 2.0, -1e-300, 123456789.125]);
        let text = String::from_utf8(f64_lines(&rows)).unwrap();
        let back: Vec<Vec<f64>> =
            text.lines().map(|l| l.split(' ').map(|x| x.parse::<f64>().unwrap()).collect()).collect();
        assert_eq!(back.len(), rows.len());
        for (row, got) in rows.iter().zip(&back) {
            assert_eq!(got.len(), 8);
            for (x, y) in row.iter().zip(got) {
                assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()), "{x} read back as {y}");
            }
        }
        assert!(text.ends_with("123456789.125\n") && text.contains("NaN inf -inf"), "{text}");
    }
}
