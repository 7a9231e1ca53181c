//! Textures drawn as textures: each material group's texture bound and
//! sampled per pixel through the (refined) texture coordinates, asserted
//! on the pixels of offscreen renders. A texture red on its left half and
//! green on its right shows both colours with a sharp boundary and no
//! yellow between them (the blend that sampling per vertex and
//! interpolating gave); the wrap modes are the file's; the texture has its
//! mipmaps, averaged in linear light. Runs on any wgpu adapter; skips only
//! when none exists and SUBDIV_REQUIRE_GPU is unset.
#![cfg(feature = "viewer")]

mod common;

use common::{offscreen, scratch_dir};
use glam::{Vec2, Vec3};
use image::RgbaImage;
use std::path::{Path, PathBuf};
use subdiv::mesh::{MaterialGroups, Wrap};
use subdiv::render::MaterialDraw;
use subdiv::render::{Camera, GpuMesh, Look, Offscreen, Paint, RenderOptions};
use subdiv::{Mesh, Scheme};

/// The unit cube, every face's texture coordinates covering 0..1, counter-
/// clockwise seen from outside, all faces in material `two`.
const CUBE: &str = "mtllib cube.mtl\n\
v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
usemtl two\n\
f 5/1 6/2 7/3 8/4\nf 2/1 1/2 4/3 3/4\nf 6/1 2/2 3/3 7/4\nf 1/1 5/2 8/3 4/4\nf 8/1 7/2 3/3 4/4\nf 1/1 2/2 6/3 5/4\n";

/// A `w` x `h` PNG at `path`, left half red and right half green (or top
/// half red and bottom half green when `rows`).
fn two_colour_png(path: &Path, w: u32, h: u32, rows: bool) {
    let img = image::RgbImage::from_fn(w, h, |x, y| {
        let first = if rows { y < h / 2 } else { x < w / 2 };
        if first { image::Rgb([255, 0, 0]) } else { image::Rgb([0, 255, 0]) }
    });
    img.save(path).unwrap();
}

/// The model at `path` with its textures decoded, as `render` and the
/// viewer read it.
fn load_textured(path: &Path) -> (Mesh, subdiv::mesh::Attributes) {
    let opts = subdiv::io::ReadOptions { textures: true, ..Default::default() };
    let l = subdiv::io::read(subdiv::io::Source::File(path), &opts).unwrap();
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    (l.mesh, l.attributes)
}

/// The cube, its MTL (`map_Kd` statement `map`) and its 256 x 256 texture
/// in a fresh directory.
fn cube(name: &str, map: &str) -> PathBuf {
    let dir = scratch_dir(name);
    std::fs::write(dir.join("cube.obj"), CUBE).unwrap();
    std::fs::write(dir.join("cube.mtl"), format!("newmtl two\nKd 1 1 1\n{map}\n")).unwrap();
    two_colour_png(&dir.join("two.png"), 256, 256, false);
    dir.join("cube.obj")
}

/// Mostly `k` (0 red, 1 green): it exceeds the other two channels by
/// more than a third of itself (so a lit, a highlighted and a shadowed red
/// all count).
fn mostly(p: [u8; 4], k: usize) -> bool {
    let c = i32::from(p[k]);
    let others = (0..3).filter(|&i| i != k).map(|i| i32::from(p[i])).max().unwrap_or(0);
    c > 30 && 3 * (c - others) > c
}

fn is_red(p: [u8; 4]) -> bool {
    mostly(p, 0)
}

fn is_green(p: [u8; 4]) -> bool {
    mostly(p, 1)
}

/// Red and green alike and well lit, blue lower: what blending red into
/// green gives.
fn is_yellowish(p: [u8; 4]) -> bool {
    let (r, g, b) = (u32::from(p[0]), u32::from(p[1]), u32::from(p[2]));
    r > 60 && g > 60 && 3 * r.abs_diff(g) < r.max(g) && 4 * b < 3 * r.min(g)
}

/// Red (1) or green (2) or neither (0).
fn class(p: [u8; 4]) -> u8 {
    u8::from(is_red(p)) + 2 * u8::from(is_green(p))
}

/// Along the pixels of `line`: how many times red changes to green or
/// back, and the most pixels of neither between the two sides of a change.
fn changes(img: &RgbaImage, line: impl Iterator<Item = (u32, u32)>) -> (usize, usize) {
    let (mut count, mut widest) = (0, 0);
    let mut last: Option<(u8, usize)> = None;
    for (i, (x, y)) in line.enumerate() {
        let c = class(img.get_pixel(x, y).0);
        if c == 0 {
            continue;
        }
        if let Some((lc, li)) = last
            && lc != c
        {
            count += 1;
            widest = widest.max(i - li - 1);
        }
        last = Some((c, i));
    }
    (count, widest)
}

#[test]
fn a_two_colour_texture_on_a_cube_shows_both_colours_with_a_sharp_boundary() {
    let Some(_) = offscreen(8, 8) else { return };
    let path = cube("tex-cube", "map_Kd two.png");
    let (mesh, attrs) = load_textured(&path);
    // through one level of refined texture coordinates (midpoint keeps the cube)
    let opts = subdiv::Options::default();
    let (fine, _) = subdiv::subdivide(&mesh, Scheme::Midpoint, 1, &opts).unwrap();
    let r = subdiv::Refiner::new(&mesh, Scheme::Midpoint, 1, &opts).unwrap().attributes(&attrs).unwrap();
    let paint = Paint::Materials { groups: r.materials.unwrap(), uv: r.uv };
    let ropts = RenderOptions { width: 240, height: 200, ..Default::default() };
    let img = subdiv::render::render_image_painted(&fine, None, &ropts, &paint).unwrap();
    img.save(path.with_file_name("cube.png")).unwrap();
    let (red, green) = (img.pixels().filter(|p| is_red(p.0)).count(), img.pixels().filter(|p| is_green(p.0)).count());
    let area = (240 * 200) as usize;
    assert!(red > area / 20 && green > area / 20, "red {red}, green {green} of {area} pixels");
    // the rows of the two side faces in view (above them the top face,
    // seen at a grazing angle, has its boundary almost along the rows):
    // red meets green within a few pixels
    let band = 80..170;
    let (mut count, mut widest, mut at) = (0, 0, 0);
    for y in band.clone() {
        let (c, w) = changes(&img, (0..240).map(|x| (x, y)));
        count += c;
        if w > widest {
            (widest, at) = (w, y);
        }
    }
    assert!(count >= 2 * band.len(), "{count} changes from red to green along {} rows", band.len());
    assert!(widest <= 3, "a change from red to green takes {widest} pixels in row {at}");
    // the blend of the two is the pixel or two where they meet, not a band
    let yellow = band.flat_map(|y| (0..240).map(move |x| (x, y))).filter(|&(x, y)| is_yellowish(img.get_pixel(x, y).0));
    let yellow = yellow.count();
    assert!(yellow <= 2 * count, "{yellow} yellowish pixels at {count} changes from red to green");
}

/// A square of side 2 in the z = 0 plane facing +z, two triangles, its
/// texture coordinates running over `lo..hi` along both axes.
fn square(lo: f32, hi: f32) -> (Mesh, Vec<Vec2>) {
    let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, y)| Vec3::new(x, y, 0.0));
    let mesh = Mesh::from_triangles(p.to_vec(), &[0, 1, 2, 0, 2, 3]).unwrap();
    let t = |v: Vec3| Vec2::new(lo + (v.x + 1.0) / 2.0 * (hi - lo), lo + (v.y + 1.0) / 2.0 * (hi - lo));
    let uv = mesh.ct.v_table().iter().map(|&v| t(mesh.positions[v as usize])).collect();
    (mesh, uv)
}

/// The square seen head on by an orthographic camera, filling the image.
fn head_on() -> Camera {
    let mut cam = Camera { yaw: 0.0, pitch: 0.0, orthographic: true, ..Camera::default() };
    cam.fit(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0), 1.0);
    cam
}

/// `mesh` with the materials `groups` and per-corner `uv`, rendered head on.
fn draw(off: &mut Offscreen, mesh: &Mesh, uv: &[Vec2], groups: &MaterialGroups) -> (RgbaImage, GpuMesh) {
    let (device, queue) = (&off.gpu.device, &off.gpu.queue);
    let materials = MaterialDraw { groups, uv: Some(uv), reuse: None };
    let g = GpuMesh::textured(device, queue, &mesh.ct, &mesh.positions, &mesh.vertex_normals(), materials).unwrap();
    let img = off.render_one(head_on(), &g, None, Look { materials: true, ..Look::default() }).unwrap();
    (img, g)
}

/// The material groups of a two-triangle model with the one material of
/// the MTL whose `map_Kd` statement is `map` (texture split along `rows`).
fn groups_from_mtl(name: &str, map: &str, rows: bool) -> MaterialGroups {
    let dir = scratch_dir(name);
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl t\nf 1 2 3\nf 1 3 4\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    std::fs::write(dir.join("m.mtl"), format!("newmtl t\nKd 1 1 1\n{map}\n")).unwrap();
    two_colour_png(&dir.join("t.png"), 64, 64, rows);
    load_textured(&dir.join("m.obj")).1.materials.unwrap()
}

#[test]
fn repeat_clamp_and_mirror_are_the_files() {
    let Some(mut off) = offscreen(120, 120) else { return };
    // texture coordinates -1..2: three copies of the texture across the square
    let (mesh, uv) = square(-1.0, 2.0);
    let row = |img: &RgbaImage| changes(img, (0..120).map(|x| (x, 60))).0;
    let column = |img: &RgbaImage| changes(img, (0..120).map(|y| (60, y))).0;
    let repeat = groups_from_mtl("tex-repeat", "map_Kd t.png", false);
    let (img, _) = draw(&mut off, &mesh, &uv, &repeat);
    // red, green at -1..0, 0..1 and 1..2
    assert_eq!(row(&img), 5, "repeated");
    let mut clamp = groups_from_mtl("tex-clamp", "map_Kd -clamp on t.png", false);
    assert_eq!(clamp.list[0].wrap, [Wrap::Clamp; 2]);
    let (img, _) = draw(&mut off, &mesh, &uv, &clamp);
    // the left column's red below 0, the right column's green above 1
    assert_eq!(row(&img), 1, "clamped");
    clamp.list[0].wrap = [Wrap::Mirror; 2];
    let (img, _) = draw(&mut off, &mesh, &uv, &clamp);
    // green red | red green | green red
    assert_eq!(row(&img), 3, "mirrored");
    // each axis its own mode (glTF's wrapS and wrapT): the texture split
    // into a red top and a green bottom changes only along v
    let mut rows = groups_from_mtl("tex-rows", "map_Kd t.png", true);
    rows.list[0].wrap = [Wrap::Repeat, Wrap::Clamp];
    let (img, _) = draw(&mut off, &mesh, &uv, &rows);
    assert_eq!((row(&img), column(&img)), (0, 1), "clamped along v");
    rows.list[0].wrap = [Wrap::Clamp, Wrap::Repeat];
    let (img, _) = draw(&mut off, &mesh, &uv, &rows);
    assert_eq!((row(&img), column(&img)), (0, 5), "repeated along v");
}

#[test]
fn a_minified_checker_is_its_linear_average_grey_through_the_mipmaps() {
    let Some(mut off) = offscreen(57, 57) else { return };
    let dir = scratch_dir("tex-mip");
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl c\nf 1 2 3\nusemtl grey\nf 1 3 4\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl c\nKd 1 1 1\nmap_Kd c.png\nnewmtl grey\nKd 0.5 0.5 0.5\n").unwrap();
    // black and white pixels in a checker, 256 x 256: on 57 pixels every
    // pixel covers 4.5 of them, which sampled without mipmaps is noise
    let img = image::RgbImage::from_fn(256, 256, |x, y| image::Rgb([if (x + y) % 2 == 0 { 0 } else { 255 }; 3]));
    img.save(dir.join("c.png")).unwrap();
    let mut groups = load_textured(&dir.join("m.obj")).1.materials.unwrap();
    let (mesh, uv) = square(0.0, 1.0);
    groups.face = vec![0, 0];
    let (checker, g) = draw(&mut off, &mesh, &uv, &groups);
    groups.face = vec![1, 1];
    let (grey, _) = draw(&mut off, &mesh, &uv, &groups);
    checker.save(dir.join("checker.png")).unwrap();
    // the middle of the square: as flat as the grey of a linear 0.5, not
    // the darker grey of averaging the sRGB bytes
    let (mut most, mut sum, mut n) = (0u8, 0.0, 0.0);
    for y in 14..43 {
        for x in 14..43 {
            let (c, g) = (checker.get_pixel(x, y).0[0], grey.get_pixel(x, y).0[0]);
            most = most.max(c.abs_diff(g));
            (sum, n) = (sum + f64::from(c) - f64::from(g), n + 1.0);
        }
    }
    assert!(most <= 4, "a pixel of the minified checker is {most} from the grey");
    assert!((sum / n).abs() <= 4.0, "the minified checker is {} from the grey on average", sum / n);
    // the checker's 256, 128, ..., 1 and the white texel of the flat grey
    assert_eq!(g.materials().unwrap().mip_level_counts(), [9, 1]);
}

#[test]
fn gltf_wrap_modes_are_read_per_axis_with_the_base_colour() {
    let dir = scratch_dir("tex-gltf");
    let mut bin: Vec<u8> =
        [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|f| f.to_le_bytes()).collect();
    bin.extend([0u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    std::fs::write(dir.join("tri.bin"), &bin).unwrap();
    two_colour_png(&dir.join("t.png"), 8, 8, false);
    let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
        "buffers":[{"uri":"tri.bin","byteLength":48}],
        "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                     {"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}],
        "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.25,1],"baseColorTexture":{"index":0}}}],
        "textures":[{"source":0,"sampler":0}],"samplers":[{"wrapS":33648,"wrapT":33071}],"images":[{"uri":"t.png"}]}"#;
    std::fs::write(dir.join("m.gltf"), json).unwrap();
    let groups = load_textured(&dir.join("m.gltf")).1.materials.unwrap();
    let m = &groups.list[0];
    assert_eq!(m.wrap, [Wrap::Mirror, Wrap::Clamp], "wrapS MIRRORED_REPEAT, wrapT CLAMP_TO_EDGE");
    assert_eq!(m.diffuse, Vec3::new(1.0, 0.5, 0.25));
    assert_eq!(m.texture.as_ref().map(|t| (t.width, t.height)), Some((8, 8)));
}

#[test]
fn a_texture_whose_pixels_do_not_fill_its_size_is_drawn_flat() {
    let Some(mut off) = offscreen(64, 64) else { return };
    let mut groups = groups_from_mtl("tex-short", "map_Kd t.png", false);
    let short = subdiv::mesh::Texture { width: 64, height: 64, rgba: vec![255, 0, 0, 255] };
    groups.list[0].texture = Some(std::sync::Arc::new(short));
    let (mesh, uv) = square(0.0, 1.0);
    let (img, g) = draw(&mut off, &mesh, &uv, &groups);
    // its Kd (white) alone: no red, and only the white texel bound
    assert_eq!(img.pixels().filter(|p| is_red(p.0)).count(), 0);
    assert_eq!(g.materials().unwrap().mip_level_counts(), [1]);
}
