//! The hostile and misread inputs of `tests/hostile.rs`, built at run time
//! (no binary file is committed), and [`hostile_seeds`]: the single-file ones
//! as fuzz seeds for `tests/io.rs` (`mod hostile_inputs;` there, then
//! `hostile_inputs::hostile_seeds()`).
//!
//! Images are written by hand (PNG chunks with their CRCs, a zlib stream of
//! fixed-Huffman matches, GIF blocks, JPEG markers), so that a small file
//! can declare a huge image without the test holding the pixels.
#![allow(dead_code)]

// ---------------------------------------------------------------- encoders

/// Standard base64 with padding.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n =
            (u32::from(c[0]) << 16) | (u32::from(*c.get(1).unwrap_or(&0)) << 8) | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// CRC-32 (IEEE, as PNG uses it).
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
        }
    }
    !c
}

/// Bits written least significant first, as deflate packs them.
struct Bits {
    out: Vec<u8>,
    acc: u64,
    n: u32,
}

impl Bits {
    fn new() -> Bits {
        Bits { out: Vec::new(), acc: 0, n: 0 }
    }
    fn put(&mut self, value: u32, bits: u32) {
        self.acc |= u64::from(value) << self.n;
        self.n += bits;
        while self.n >= 8 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.n -= 8;
        }
    }
    /// A Huffman code, most significant bit first.
    fn code(&mut self, code: u32, bits: u32) {
        let rev = code.reverse_bits() >> (32 - bits);
        self.put(rev, bits);
    }
    fn finish(mut self) -> Vec<u8> {
        if self.n > 0 {
            self.out.push(self.acc as u8);
        }
        self.out
    }
}

/// A zlib stream of `n` zero bytes: one fixed-Huffman block, a literal 0 and
/// then matches of 258 bytes at distance 1 (13 bits each: about 160 to 1).
pub fn zlib_zeros(n: u64) -> Vec<u8> {
    let mut b = Bits::new();
    b.put(1, 1); // BFINAL
    b.put(1, 2); // BTYPE 01: fixed Huffman
    let lit0 = |b: &mut Bits| b.code(0x30, 8);
    let mut left = n;
    if left > 0 {
        lit0(&mut b);
        left -= 1;
    }
    while left >= 258 {
        b.code(0xC5, 8); // length symbol 285 (258), no extra bits
        b.code(0, 5); // distance code 0 (1)
        left -= 258;
    }
    for _ in 0..left {
        lit0(&mut b);
    }
    b.code(0, 7); // end of block (256)
    let mut z = vec![0x78, 0x01];
    z.extend(b.finish());
    // Adler-32 of zeros: a = 1, b = n (mod 65521)
    let adler = (((n % 65521) as u32) << 16) | 1;
    z.extend(adler.to_be_bytes());
    z
}

fn png_chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let mut c = kind.to_vec();
    c.extend_from_slice(data);
    out.extend_from_slice(&c);
    out.extend(crc32(&c).to_be_bytes());
}

/// A PNG whose header declares `w` x `h` pixels of `depth`-bit `color`
/// (0 grey, 2 RGB) and whose IDAT holds `idat`.
pub fn png(w: u32, h: u32, depth: u8, color: u8, idat: &[u8]) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = Vec::new();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([depth, color, 0, 0, 0]);
    png_chunk(&mut out, b"IHDR", &ihdr);
    png_chunk(&mut out, b"IDAT", idat);
    png_chunk(&mut out, b"IEND", &[]);
    out
}

/// A 2 x 2 RGB PNG (a legitimate texture), all pixels grey 128.
pub fn png_small() -> Vec<u8> {
    // two rows: filter byte 0 and 2 pixels of 3 bytes; stored (uncompressed) deflate block
    let raw: Vec<u8> = [0u8, 128, 128, 128, 128, 128, 128].repeat(2);
    let mut z = vec![0x78, 0x01, 0x01];
    z.extend((raw.len() as u16).to_le_bytes());
    z.extend((!(raw.len() as u16)).to_le_bytes());
    z.extend(&raw);
    let (mut a, mut b) = (1u32, 0u32);
    for &x in &raw {
        a = (a + u32::from(x)) % 65521;
        b = (b + a) % 65521;
    }
    z.extend(((b << 16) | a).to_be_bytes());
    png(2, 2, 8, 2, &z)
}

/// A PNG declaring 60000 x 60000 RGB pixels (10.8 GB) with a 20-byte IDAT.
pub fn png_declared_huge() -> Vec<u8> {
    png(60000, 60000, 8, 2, &zlib_zeros(1000))
}

/// A complete 1-bit grey PNG of 20000 x 20000 zero pixels in about 315 KB:
/// 400 MB once expanded to 8 bits (inside `image`'s 512 MiB decode limit),
/// 4.8 GB as RGB floats (x12).
pub fn png_grey_float_bomb() -> Vec<u8> {
    let (w, h) = (20000u32, 20000u32);
    let row = 1 + u64::from(w).div_ceil(8);
    png(w, h, 1, 0, &zlib_zeros(row * u64::from(h)))
}

/// A GIF whose logical screen is `w` x `h` with one 1 x 1 frame.
pub fn gif_screen(w: u16, h: u16) -> Vec<u8> {
    let mut g = b"GIF89a".to_vec();
    g.extend(w.to_le_bytes());
    g.extend(h.to_le_bytes());
    g.extend([0x80, 0, 0]); // global colour table of 2 entries
    g.extend([0, 0, 0, 255, 255, 255]);
    g.push(0x2C); // image descriptor: at (0, 0), 1 x 1, no local table
    g.extend([0, 0, 0, 0, 1, 0, 1, 0, 0]);
    // LZW, minimum code size 2: clear (4), index 0, end (5) in 3-bit codes
    g.extend([2, 2, 0x44, 0x01, 0]);
    g.push(0x3B);
    g
}

/// A baseline grey JPEG of `w` x `h` (SOF0, one component). With `scan`
/// the entropy-coded data is complete (every 8 x 8 block a zero DC
/// difference and an end of block, 2 bits); without it the scan is 16 bytes.
pub fn jpeg_grey(w: u16, h: u16, scan: bool) -> Vec<u8> {
    let mut j = vec![0xFF, 0xD8];
    // quantisation table 0: all ones
    j.extend([0xFF, 0xDB, 0, 67, 0]);
    j.extend([1u8; 64]);
    // frame: 8-bit, h, w, one component (id 1, 1x1 sampling, table 0)
    j.extend([0xFF, 0xC0, 0, 11, 8]);
    j.extend(h.to_be_bytes());
    j.extend(w.to_be_bytes());
    j.extend([1, 1, 0x11, 0]);
    // Huffman tables: DC 0 and AC 0, each a single 1-bit code for symbol 0
    for class in [0x00u8, 0x10] {
        j.extend([0xFF, 0xC4, 0, 20, class]);
        let mut counts = [0u8; 16];
        counts[0] = 1;
        j.extend(counts);
        j.push(0);
    }
    // scan: one component, tables 0/0, spectral 0..63
    j.extend([0xFF, 0xDA, 0, 8, 1, 1, 0x00, 0, 63, 0]);
    let blocks = u64::from(w).div_ceil(8) * u64::from(h).div_ceil(8);
    let bytes = if scan { (2 * blocks).div_ceil(8) } else { 16 };
    j.extend(std::iter::repeat_n(0u8, bytes as usize));
    j.extend([0xFF, 0xD9]);
    j
}

// ---------------------------------------------------------------- glTF

/// Little-endian bytes of `f32`s.
pub fn f32s(xs: &[f32]) -> Vec<u8> {
    xs.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// A `data:` URI of `bytes`.
pub fn data_uri(bytes: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", base64(bytes))
}

/// The triangle (0,0,0) (1,0,0) (0,1,0) with u16 indices 0 1 2: 36 bytes
/// of positions and 6 of indices (42 bytes).
pub fn triangle_buffer() -> Vec<u8> {
    let mut b = f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    b.extend([0u8, 0, 1, 0, 2, 0]);
    b
}

/// A `.gltf` of one triangle whose buffer is at `uri` (42 bytes declared),
/// drawn by `nodes_json` (default one node with mesh 0).
pub fn gltf_triangle(uri: &str) -> String {
    gltf_with(uri, 42, r#"{"mesh":0}"#, "[0]", r#"{"attributes":{"POSITION":0},"indices":1}"#, "")
}

/// A `.gltf` with one buffer (`uri`, `len` bytes), the triangle's two views
/// and accessors, the given node list, scene root list and primitive list,
/// and `extra` top-level members (each starting with a comma).
pub fn gltf_with(uri: &str, len: usize, nodes: &str, roots: &str, primitives: &str, extra: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":{roots}}}],"nodes":[{nodes}],"meshes":[{{"primitives":[{primitives}]}}],"buffers":[{{"byteLength":{len},"uri":"{uri}"}}],"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}]{extra}}}"#
    )
}

/// A triangle whose POSITION view has a byte stride of 4, smaller than its
/// 12-byte elements (legal JSON, invalid glTF): the range check passes with
/// `max(stride, size)` and the crate asserts on the real stride.
pub fn gltf_stride_too_small() -> String {
    let b = triangle_buffer();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],"buffers":[{{"byteLength":42,"uri":"{}"}}],"bufferViews":[{{"buffer":0,"byteLength":36,"byteStride":4}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}]}}"#,
        data_uri(&b)
    )
}

/// The same with a valid POSITION view and a TEXCOORD_0 accessor (VEC2
/// float, 8 bytes) on a view of stride 4.
pub fn gltf_texcoord_stride_too_small() -> String {
    let mut b = triangle_buffer();
    b.extend([0u8; 2]); // align to 4
    b.extend(f32s(&[0.0; 6]));
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":2}},"indices":1}}]}}],"buffers":[{{"byteLength":68,"uri":"{}"}}],"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}},{{"buffer":0,"byteOffset":44,"byteLength":24,"byteStride":4}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}},{{"bufferView":2,"componentType":5126,"count":3,"type":"VEC2"}}]}}"#,
        data_uri(&b)
    )
}

/// A buffer of three positions followed by `n` u8 indices 0 1 2 0 1 2 ...,
/// and the JSON of its views and accessors (0: POSITION, 1: the indices).
fn strip_buffer(n: usize) -> (Vec<u8>, String) {
    let mut b = f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    b.extend((0..n).map(|i| (i % 3) as u8));
    let json = format!(
        r#""buffers":[{{"byteLength":{},"uri":"{}"}}],"bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":{n}}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},{{"bufferView":1,"componentType":5121,"count":{n},"type":"SCALAR"}}]"#,
        b.len(),
        data_uri(&b)
    );
    (b, json)
}

/// A triangle strip primitive of [`strip_buffer`].
const STRIP: &str = r#"{"attributes":{"POSITION":0},"indices":1,"mode":5}"#;

/// Amplification: one 100,000-triangle strip accessor (100 KB) repeated in
/// 4,000 primitives of one mesh: 400 million triangles from 300 KB.
pub fn gltf_repeated_primitives() -> String {
    let (_, buffers) = strip_buffer(100_002);
    let prims = vec![STRIP; 4000].join(",");
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{prims}]}}],{buffers}}}"#
    )
}

/// Amplification: a node graph of 2 x 40 nodes where both nodes of every
/// level have both nodes of the next as children (not a tree: each node has
/// two parents), the last level drawing a 10,000-triangle strip: 2^40 paths.
pub fn gltf_shared_children() -> String {
    let (_, buffers) = strip_buffer(10_002);
    let levels = 40;
    let nodes: Vec<String> = (0..2 * levels)
        .map(|i| {
            let level = i / 2;
            if level + 1 < levels {
                format!(r#"{{"children":[{},{}]}}"#, 2 * level + 2, 2 * level + 3)
            } else {
                r#"{"mesh":0}"#.to_string()
            }
        })
        .collect();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],"nodes":[{}],"meshes":[{{"primitives":[{STRIP}]}}],{buffers}}}"#,
        nodes.join(",")
    )
}

/// Amplification: a scene that lists its one root node (a 100,000-triangle
/// strip) 20,000 times: 2 billion triangles from 180 KB.
pub fn gltf_root_listed_many_times() -> String {
    let (_, buffers) = strip_buffer(100_002);
    let roots = vec!["0"; 20_000].join(",");
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[{roots}]}}],"nodes":[{{"mesh":0}}],"meshes":[{{"primitives":[{STRIP}]}}],{buffers}}}"#
    )
}

/// A legal chain of `depth` nodes, each translated by (0, 0, 1) and the
/// child of the one before, the last drawing the triangle: its vertices end
/// at z = `depth`.
pub fn gltf_chain(depth: usize) -> String {
    let mut nodes = String::with_capacity(depth * 48);
    for i in 0..depth {
        if i > 0 {
            nodes.push(',');
        }
        if i + 1 < depth {
            nodes.push_str(&format!(r#"{{"children":[{}],"translation":[0,0,1]}}"#, i + 1));
        } else {
            nodes.push_str(r#"{"mesh":0,"translation":[0,0,1]}"#);
        }
    }
    gltf_with(&data_uri(&triangle_buffer()), 42, &nodes, "[0]", r#"{"attributes":{"POSITION":0},"indices":1}"#, "")
}

/// The triangle with a material whose base colour texture is at `uri`.
pub fn gltf_textured(tex_uri: &str) -> String {
    let extra = format!(
        r#","materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],"textures":[{{"source":0}}],"images":[{{"uri":"{tex_uri}"}}]"#
    );
    gltf_with(
        &data_uri(&triangle_buffer()),
        42,
        r#"{"mesh":0}"#,
        "[0]",
        r#"{"attributes":{"POSITION":0},"indices":1,"material":0}"#,
        &extra,
    )
}

// ---------------------------------------------------------------- COLLADA

/// A COLLADA file of the unit square's 4 corners (and `extra_positions`
/// more) with `prim` as its only primitive.
pub fn dae(prim: &str, extra_positions: &str) -> String {
    let floats = format!("0 0 0 1 0 0 1 1 0 0 1 0 {extra_positions}");
    let n = floats.split_whitespace().count();
    format!(
        r##"<?xml version="1.0"?><COLLADA><library_geometries><geometry id="g"><mesh><source id="p"><float_array id="pa" count="{n}">{floats}</float_array><technique_common><accessor source="#pa" count="{}" stride="3"/></technique_common></source><vertices id="v"><input semantic="POSITION" source="#p"/></vertices>{prim}</mesh></geometry></library_geometries></COLLADA>"##,
        n / 3
    )
}

/// Two triangles whose `<p>` has a comment between them: the text is two
/// runs, and only the first was read.
pub fn dae_comment_in_p() -> String {
    dae(
        r##"<triangles count="2"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2 <!-- the second triangle --> 0 2 3</p></triangles>"##,
        "",
    )
}

/// A `<polygons>` with one triangle and one `<ph>` (a square with a
/// triangular hole): the `<ph>` was dropped without a word.
pub fn dae_ph_hole() -> String {
    dae(
        r##"<polygons count="2"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p><ph><p>4 5 6 7</p><h>8 9 10</h></ph></polygons>"##,
        "2 0 0 6 0 0 6 4 0 2 4 0 3 1 0 5 1 0 4 3 0",
    )
}

/// A `<polylist>` whose `<vcount>` covers one triangle while `<p>` holds
/// two: the second was ignored.
pub fn dae_beyond_vcount() -> String {
    dae(
        r##"<polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/><vcount>3</vcount><p>0 1 2 0 2 3</p></polylist>"##,
        "",
    )
}

// ---------------------------------------------------------------- STL, OFF, PLY

/// A binary STL with two facets (the unit square) whose header claims one.
pub fn stl_count_smaller_than_data() -> Vec<u8> {
    let mut b = vec![b' '; 80];
    b.extend(1u32.to_le_bytes());
    for tri in
        [[[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]], [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]]
    {
        b.extend(f32s(&[0.0, 0.0, 1.0]));
        for p in tri {
            b.extend(f32s(&p));
        }
        b.extend([0, 0]);
    }
    b
}

/// An OFF whose header claims one face and which has two face lines.
pub const OFF_FACES_BEYOND_COUNT: &str = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

/// A `4OFF` (homogeneous coordinates x y z w): the triangle (0,0,0) (1,0,0)
/// (0,1,0) with w = 1, 2 and 4.
pub const OFF_4D: &str = "4OFF\n3 1 0\n0 0 0 1\n2 0 0 2\n0 4 0 4\n3 0 1 2\n";

/// A `CNOFF`: normals (0, 0, 1) before colours (0.25, 0.5, 0.75, 1).
pub const CNOFF: &str =
    "CNOFF\n3 1 0\n0 0 0 0 0 1 0.25 0.5 0.75 1\n1 0 0 0 0 1 0.25 0.5 0.75 1\n0 1 0 0 0 1 0.25 0.5 0.75 1\n3 0 1 2\n";

const PLY_SQUARE_VERTICES: &str = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

/// MeshLab's per-face `texcoord`: a list of floats beside the indices.
pub fn ply_float_list_texcoord() -> String {
    format!(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n{PLY_SQUARE_VERTICES}3 0 1 2 6 0 0 1 0 1 1\n3 0 2 3 6 0 0 1 1 0 1\n"
    )
}

/// An ASCII PLY (the square, 2 faces) whose first comment says `end_header`.
pub fn ply_end_header_in_comment_ascii() -> String {
    format!(
        "ply\nformat ascii 1.0\ncomment the header ends at end_header below\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n{PLY_SQUARE_VERTICES}3 0 1 2\n3 0 2 3\n"
    )
}

/// A binary PLY (the square, 2 faces) whose last comment, just before the
/// real end, is `comment end_header`.
pub fn ply_end_header_in_comment_binary() -> Vec<u8> {
    let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\ncomment end_header\nend_header\n".to_vec();
    b.extend(f32s(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]));
    for f in [[0u32, 1, 2], [0, 2, 3]] {
        b.push(3);
        b.extend(f.iter().flat_map(|i| i.to_le_bytes()));
    }
    b
}

/// An ASCII PLY face whose list count is 3.5.
pub fn ply_fractional_count() -> String {
    format!(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n{PLY_SQUARE_VERTICES}3.5 0 1 2\n"
    )
}

// ---------------------------------------------------------------- OBJ, MTL

/// A closed tetrahedron (OBJ), every edge interior.
pub const TETRA_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// The tetrahedron as a `.ct`.
pub const TETRA_CT: &str = "4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n4\n0 2 1\n0 1 3\n0 3 2\n1 2 3\n";

/// An OBJ whose edge (1, 2) is shared by `n` faces (a fan of fins): the
/// non-manifold edge error listed every face.
pub fn obj_fin_fan(n: usize) -> String {
    let mut s = String::from("v 0 0 0\nv 1 0 0\n");
    for k in 0..n {
        let a = k as f32 * 0.001;
        s.push_str(&format!("v {} 1 {}\n", a.cos(), a.sin()));
    }
    for k in 0..n {
        s.push_str(&format!("f 1 2 {}\n", k + 3));
    }
    s
}

/// A one-triangle OBJ followed by `n` distinct `usemtl` names (and no
/// library): a linear search per name, one warning per name.
pub fn obj_many_usemtl(n: usize) -> String {
    let mut s = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl first\nf 1 2 3\n");
    for k in 0..n {
        s.push_str(&format!("usemtl m{k}\n"));
    }
    s
}

/// A one-triangle OBJ naming `n` distinct missing libraries.
pub fn obj_many_missing_mtllibs(n: usize) -> String {
    let mut s = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for k in 0..n {
        s.push_str(&format!("mtllib missing{k}.mtl\n"));
    }
    s.push_str("usemtl a\nf 1 2 3\n");
    s
}

/// A textured unit triangle (with `vt`) that uses material `a` of `lib`.
pub fn obj_using(lib: &str) -> String {
    format!("mtllib {lib}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n")
}

/// The OBJ text of a line `token` long in the places its reader echoes:
/// (what, file name, bytes).
pub fn long_token_files(token: &str) -> Vec<(&'static str, &'static str, Vec<u8>)> {
    vec![
        ("OBJ vertex coordinate", "long.obj", format!("v 1 1 {token}\n").into_bytes()),
        ("OBJ face index", "long.obj", format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {token}\n").into_bytes()),
        ("OBJ texture index", "long.obj", format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/{token} 2/1 3/1\n").into_bytes()),
        ("OBJ tag count", "long.obj", format!("{TETRA_OBJ}t crease {token} 0 1 2\n").into_bytes()),
        ("CT token", "long.ct", format!("3\n0 0 {token}\n").into_bytes()),
        ("PLY header line", "long.ply", format!("ply\nformat ascii 1.0\n{token}\nend_header\n").into_bytes()),
        ("PLY property type", "long.ply", format!("ply\nformat ascii 1.0\nelement vertex 1\nproperty {token} x\nend_header\n").into_bytes()),
        ("PLY element count", "long.ply", format!("ply\nformat ascii 1.0\nelement vertex {token}\nend_header\n").into_bytes()),
        ("PLY format", "long.ply", format!("ply\nformat {token} 1.0\nend_header\n").into_bytes()),
        ("STL keyword", "long.stl", format!("solid x\n{token}\nendsolid x\n").into_bytes()),
        ("STL coordinate", "long.stl", format!("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 {token}\n").into_bytes()),
        ("OFF magic", "long.off", format!("{token}OFX\n3 1 0\n").into_bytes()),
        ("OFF counts", "long.off", format!("OFF\n{token} 1 0\n").into_bytes()),
        ("glTF buffer URI", "long.gltf", gltf_triangle(token).into_bytes()),
        (
            "COLLADA geometry id",
            "long.dae",
            format!(r##"<?xml version="1.0"?><COLLADA><library_geometries><geometry id="{token}"><mesh><triangles count="1"><input semantic="VERTEX" source="#nowhere" offset="0"/><p>0 1 2</p></triangles></mesh></geometry></library_geometries></COLLADA>"##).into_bytes(),
        ),
        (
            "COLLADA source reference",
            "long.dae",
            dae(&format!(r##"<triangles count="1"><input semantic="VERTEX" source="#{token}" offset="0"/><p>0 1 2</p></triangles>"##), "").into_bytes(),
        ),
        (
            "COLLADA input semantic",
            "long.dae",
            dae(&format!(r##"<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><input semantic="{token}" source="#v" offset="-1"/><p>0 1 2</p></triangles>"##), "").into_bytes(),
        ),
    ]
}

/// Files whose errors quote control bytes (NUL, ESC, CR, BEL) from the
/// data: (what, file name, bytes).
pub fn control_byte_files() -> Vec<(&'static str, &'static str, Vec<u8>)> {
    vec![
        ("OBJ keyword with NULs", "nul.obj", b"v 0 0 0\n\0\0\0\x1b[2Jbad 1 2\n".to_vec()),
        ("OBJ coordinate with NUL", "nul.obj", b"v 0 0 0\x001\n".to_vec()),
        ("PLY header line", "nul.ply", b"ply\nformat ascii 1.0\n\x1b[31m\0\x07\rbad\nend_header\n".to_vec()),
        ("STL keyword", "nul.stl", b"solid x\n\x1b]0;title\x07\0\nendsolid x\n".to_vec()),
        ("OFF magic", "nul.off", b"\x1b[2J\0\x07OFF\n3 1 0\n".to_vec()),
        ("glTF buffer URI", "nul.gltf", gltf_triangle("\\u0000\\u001b[2J\\r.bin").into_bytes()),
    ]
}

// ---------------------------------------------------------------- seeds

/// The single-file hostile inputs above as fuzz seeds `(name with
/// extension, bytes)`. Long lines are 64 KB here (3 MB in the tests) to keep
/// the fuzz rounds fast; the image bombs are left out (they are textures,
/// not meshes, and 300 KB to 1 MB each).
///
/// Under the current readers some of these abort or hang (the glTF
/// amplification files, `/dev/zero` and `/dev/stdin` buffer URIs, the stride
/// assertion): add them to `tests/io.rs` together with the fix.
pub fn hostile_seeds() -> Vec<(&'static str, Vec<u8>)> {
    let mut s: Vec<(&'static str, Vec<u8>)> = vec![
        ("stride.gltf", gltf_stride_too_small().into_bytes()),
        ("texcoord_stride.gltf", gltf_texcoord_stride_too_small().into_bytes()),
        ("primitives.gltf", gltf_repeated_primitives().into_bytes()),
        ("shared_children.gltf", gltf_shared_children().into_bytes()),
        ("roots.gltf", gltf_root_listed_many_times().into_bytes()),
        ("chain.gltf", gltf_chain(1000).into_bytes()),
        ("dev_zero.gltf", gltf_triangle("/dev/zero").into_bytes()),
        ("dev_stdin.gltf", gltf_triangle("/dev/stdin").into_bytes()),
        ("dotdot.gltf", gltf_triangle("../x.bin").into_bytes()),
        ("percent.gltf", gltf_triangle("%2e%2e/x.bin").into_bytes()),
        ("texture.gltf", gltf_textured("../t.png").into_bytes()),
        ("comment.dae", dae_comment_in_p().into_bytes()),
        ("ph.dae", dae_ph_hole().into_bytes()),
        ("vcount.dae", dae_beyond_vcount().into_bytes()),
        ("count.stl", stl_count_smaller_than_data()),
        ("faces.off", OFF_FACES_BEYOND_COUNT.as_bytes().to_vec()),
        ("homogeneous.off", OFF_4D.as_bytes().to_vec()),
        ("normals.off", CNOFF.as_bytes().to_vec()),
        ("texcoord.ply", ply_float_list_texcoord().into_bytes()),
        ("comment.ply", ply_end_header_in_comment_ascii().into_bytes()),
        ("comment_binary.ply", ply_end_header_in_comment_binary()),
        ("fraction.ply", ply_fractional_count().into_bytes()),
        ("tags.obj", format!("{TETRA_OBJ}t crease 2/1/0 0 1 3\nt crease 2/1/0 0 1 0\n").into_bytes()),
        ("fins.obj", obj_fin_fan(2000).into_bytes()),
        ("usemtl.obj", obj_many_usemtl(2000).into_bytes()),
    ];
    let token = "9".repeat(64 << 10);
    s.extend(long_token_files(&token).into_iter().map(|(_, name, b)| (name, b)));
    s.extend(control_byte_files().into_iter().map(|(_, name, b)| (name, b)));
    s
}
