//! MTL materials: `usemtl` groups read with their `Kd` and `map_Kd`, carried through the 1-to-4 split (each child triangle keeps its
//! parent's material), written back as `mtllib`/`usemtl`, and drawn: the
//! texture sampled through the refined texture coordinates, red where the
//! texture is red (tests/textures.rs asserts it per pixel). The model, its MTL and its PNG are written here.

mod common;
use common::{load_with_attributes, scratch_dir, with_attributes};
use glam::Vec3;
use std::path::PathBuf;
use subdiv::Scheme;
use subdiv::mesh::refine_face_ids;

/// Two unit squares side by side in the z = 0 plane: the left one textured
/// (material `tex`, UVs 0..1), the right one plain green (`green`).
const OBJ: &str = "mtllib two.mtl\n\
v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n\
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
usemtl tex\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n\
usemtl green\nf 2/1 5/2 6/3\nf 2/1 6/3 3/4\n";

const MTL: &str = "newmtl tex\nKd 1 1 1\nmap_Kd two.png\n\nnewmtl green\nKd 0 1 0\n";

/// The model in a fresh directory; with the viewer feature also its texture:
/// 4 x 2 pixels, the left half red, the right half blue.
fn model(name: &str) -> PathBuf {
    let dir = scratch_dir(name);
    std::fs::write(dir.join("two.obj"), OBJ).unwrap();
    std::fs::write(dir.join("two.mtl"), MTL).unwrap();
    let img =
        image::RgbImage::from_fn(4, 2, |x, _| if x < 2 { image::Rgb([255, 0, 0]) } else { image::Rgb([0, 0, 255]) });
    img.save(dir.join("two.png")).unwrap();
    dir.join("two.obj")
}

#[test]
fn usemtl_groups_read_their_mtl() {
    let path = model("mtl-read");
    let (mesh, attrs) = load_with_attributes(&path);
    assert_eq!(mesh.ct.num_triangles(), 4);
    let g = attrs.materials.expect("material groups");
    assert_eq!(g.face, vec![0, 0, 1, 1]);
    assert_eq!(g.libraries, vec!["two.mtl".to_string()]);
    assert_eq!((g.list[0].name.as_str(), g.list[0].diffuse), ("tex", Vec3::ONE));
    assert_eq!(g.list[0].diffuse_texture.as_deref(), Some(path.with_file_name("two.png").as_path()));
    assert_eq!(
        (g.list[1].name.as_str(), g.list[1].diffuse, g.list[1].diffuse_texture.is_none()),
        ("green", Vec3::Y, true)
    );
    // a missing library is not an error: the groups stay, drawn grey
    let (_, a) = with_attributes(OBJ.replace("two.mtl", "none.mtl").as_bytes(), "/nowhere/x.obj").unwrap();
    let g = a.materials.unwrap();
    assert_eq!((g.face.clone(), g.list[0].diffuse), (vec![0, 0, 1, 1], Vec3::splat(0.8)));
}

/// Whether `p` is in triangle `abc` of the z = 0 plane (with a tolerance).
fn inside(p: Vec3, [a, b, c]: [Vec3; 3]) -> bool {
    let cross = |o: Vec3, u: Vec3, v: Vec3| (u - o).truncate().perp_dot((v - o).truncate());
    let (d1, d2, d3) = (cross(a, b, p), cross(b, c, p), cross(c, a, p));
    let e = -1e-6;
    (d1 >= e && d2 >= e && d3 >= e) || (d1 <= -e && d2 <= -e && d3 <= -e)
}

#[test]
fn each_child_triangle_keeps_its_parents_material() {
    // midpoint subdivision keeps every point on its parent triangle, so the
    // parent of each child is the control triangle holding its centroid
    let path = model("mtl-split");
    let (mesh, attrs) = load_with_attributes(&path);
    let levels = 3;
    let (fine, _) = subdiv::subdivide(&mesh, Scheme::Midpoint, levels, &Default::default()).unwrap();
    let refined =
        subdiv::Refiner::new(&mesh, Scheme::Midpoint, levels, &Default::default()).unwrap().attributes(&attrs).unwrap();
    let face = refined.materials.unwrap().face;
    assert_eq!(face.len(), fine.ct.num_triangles());
    let coarse: Vec<[Vec3; 3]> =
        mesh.ct.v_table().chunks(3).map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize])).collect();
    for (t, tri) in fine.ct.v_table().chunks(3).enumerate() {
        let centroid = tri.iter().map(|&v| fine.positions[v as usize]).sum::<Vec3>() / 3.0;
        let parent = coarse.iter().position(|c| inside(centroid, *c)).expect("on the control mesh");
        assert_eq!(face[t], [0, 0, 1, 1][parent], "child {t} lies in control triangle {parent}");
    }
    assert_eq!(refine_face_ids(&[7, 8], 1), vec![7, 8, 7, 8, 7, 8, 7, 8]);
}

#[cfg(feature = "cli")]
#[test]
fn subdivide_writes_mtllib_and_usemtl_back() {
    let path = model("mtl-write");
    let out = path.with_file_name("out.obj");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(["subdivide", path.to_str().unwrap(), out.to_str().unwrap(), "-n", "2"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.lines().any(|l| l == "mtllib two.mtl"), "mtllib kept");
    let (mesh, attrs) = load_with_attributes(&out);
    let g = attrs.materials.unwrap();
    assert_eq!(g.face, refine_face_ids(&[0, 0, 1, 1], 2), "one usemtl per run, same groups");
    assert_eq!(mesh.ct.num_triangles(), 64);
    assert_eq!(g.list[1].diffuse, Vec3::Y, "the library is found beside the output");
}

#[cfg(feature = "viewer")]
mod drawn {
    use super::*;
    use subdiv::mesh::MaterialGroups;

    /// The colour of each corner: its material's `Kd` times the texture at
    /// the corner's texture coordinate (the CPU's reference sampler, what
    /// the GPU samples there at full size).
    fn corner_colors(groups: &MaterialGroups, uv: Option<&[glam::Vec2]>) -> Vec<Vec3> {
        let uv = uv.unwrap();
        (0..uv.len())
            .map(|c| {
                let m = &groups.list[groups.face[c / 3] as usize];
                let tex = m.texture.as_ref().map_or(Vec3::ONE, |t| subdiv::render::sample_material(t, uv[c], m.wrap));
                m.diffuse * tex
            })
            .collect()
    }

    /// The model with its textures decoded, as the viewer and `render` read it.
    fn load_textured(path: &std::path::Path) -> (subdiv::Mesh, subdiv::mesh::Attributes) {
        let opts = subdiv::io::ReadOptions { textures: true, ..Default::default() };
        let l = subdiv::io::read(subdiv::io::Source::File(path), &opts).unwrap();
        assert!(l.warnings.is_empty(), "{:?}", l.warnings);
        (l.mesh, l.attributes)
    }

    fn red(c: Vec3) -> bool {
        c.x > 0.9 && c.y < 0.1 && c.z < 0.1
    }

    #[test]
    fn the_texture_is_sampled_through_the_refined_uvs() {
        let path = model("mtl-sample");
        let (mesh, attrs) = load_textured(&path);
        let r = subdiv::Refiner::new(&mesh, Scheme::Loop, 3, &Default::default()).unwrap().attributes(&attrs).unwrap();
        let (uv, groups) = (r.uv.unwrap(), r.materials.unwrap());
        let colors = corner_colors(&groups, Some(&uv));
        assert_eq!(colors.len(), uv.len());
        let (mut reds, mut blues, mut greens) = (0, 0, 0);
        for (c, (col, t)) in colors.iter().zip(&uv).enumerate() {
            match groups.face[c / 3] {
                // away from the texture's middle column and its wrapped edge
                0 if t.x > 0.1 && t.x < 0.4 => {
                    assert!(red(*col), "corner {c} at {t}: {col}");
                    reds += 1;
                }
                0 if t.x > 0.6 && t.x < 0.9 => {
                    assert!(col.z > 0.9 && col.x < 0.1, "corner {c} at {t}: {col}");
                    blues += 1;
                }
                1 => {
                    assert_eq!(*col, Vec3::Y, "the green group");
                    greens += 1;
                }
                _ => {}
            }
        }
        assert!(reds > 50 && blues > 50 && greens > 100, "{reds} {blues} {greens}");
    }

    #[test]
    fn a_jpeg_texture_is_read_too() {
        // most MTL files found in the wild point at JPEG textures
        let path = model("mtl-jpeg");
        let dir = path.parent().unwrap();
        let img =
            image::RgbImage::from_fn(
                32,
                16,
                |x, _| if x < 16 { image::Rgb([255, 0, 0]) } else { image::Rgb([0, 0, 255]) },
            );
        img.save(dir.join("two.jpg")).unwrap();
        std::fs::write(dir.join("two.mtl"), MTL.replace("two.png", "two.jpg")).unwrap();
        let (mesh, attrs) = load_textured(&path);
        let r = subdiv::Refiner::new(&mesh, Scheme::Loop, 2, &Default::default()).unwrap().attributes(&attrs).unwrap();
        let (uv, groups) = (r.uv.unwrap(), r.materials.unwrap());
        let colors = corner_colors(&groups, Some(&uv));
        let (mut reds, mut blues) = (0, 0);
        for (c, (col, t)) in colors.iter().zip(&uv).enumerate() {
            if groups.face[c / 3] != 0 {
                continue;
            }
            // JPEG is lossy: near the colour, not equal to it
            if t.x > 0.1 && t.x < 0.4 {
                assert!(col.x > 0.8 && col.z < 0.2, "corner {c} at {t}: {col}");
                reds += 1;
            } else if t.x > 0.6 && t.x < 0.9 {
                assert!(col.z > 0.8 && col.x < 0.2, "corner {c} at {t}: {col}");
                blues += 1;
            }
        }
        assert!(reds > 10 && blues > 10, "{reds} {blues}");
    }

    /// Pixels whose colour is mostly `channel`.
    fn count(img: &image::RgbaImage, channel: usize) -> usize {
        img.pixels()
            .filter(|p| (0..3).all(|k| k == channel || u32::from(p[channel]) > 3 * u32::from(p[k]) + 20))
            .count()
    }

    /// `subdiv render PATH OUT -n 3 --size 160x120 EXTRA..` read back, or
    /// `None` where no adapter exists (and `SUBDIV_REQUIRE_GPU` is unset).
    fn render(path: &std::path::Path, extra: &[&str]) -> Option<image::RgbaImage> {
        let out = path.with_file_name(format!("two{}.out.png", extra.join("")));
        let mut args = vec!["render", path.to_str().unwrap(), out.to_str().unwrap(), "-n", "3", "--size", "160x120"];
        args.extend_from_slice(extra);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv")).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        if !o.status.success() && err.contains("no graphics adapter") {
            assert!(std::env::var_os("SUBDIV_REQUIRE_GPU").is_none(), "SUBDIV_REQUIRE_GPU is set: {err}");
            eprintln!("SKIPPED: no GPU adapter");
            return None;
        }
        assert!(o.status.success(), "{err}");
        Some(image::open(&out).unwrap().to_rgba8())
    }

    /// The mean column of the pixels that are mostly `channel`.
    fn mean_x(img: &image::RgbaImage, ch: usize) -> f32 {
        let xs: Vec<u32> = img
            .enumerate_pixels()
            .filter(|(_, _, p)| (0..3).all(|k| k == ch || u32::from(p[ch]) > 3 * u32::from(p[k]) + 20))
            .map(|(x, ..)| x)
            .collect();
        xs.iter().sum::<u32>() as f32 / xs.len() as f32
    }

    /// Each material group is drawn in its colour, red where the texture is.
    fn assert_groups_drawn(img: &image::RgbaImage, what: &str) {
        let (r, g, b) = (count(img, 0), count(img, 1), count(img, 2));
        let area = (img.width() * img.height()) as usize;
        assert!(r > area / 100 && g > area / 100 && b > area / 100, "{what}: red {r}, green {g}, blue {b} of {area}");
        // the red half of the texture is on the left square, away from the green one:
        // the red pixels' mean column is farther from the green ones' than the blue ones'
        let (xr, xg, xb) = (mean_x(img, 0), mean_x(img, 1), mean_x(img, 2));
        assert!((xr - xg).abs() > (xb - xg).abs(), "{what}: red at {xr}, blue at {xb}, green at {xg}");
    }

    #[test]
    fn render_shows_each_group_red_where_the_texture_is_red() {
        let path = model("mtl-render");
        let Some(img) = render(&path, &["-s", "midpoint"]) else { return };
        assert_groups_drawn(&img, "phong");
        // the wireframe's own pipeline takes the same colours, and draws its
        // lines over them (the control edges only: at level 3 in 160 x 120
        // pixels all the edges would hatch the blue group pale)
        let wired = render(&path, &["-s", "midpoint", "--shading", "phong+wire", "--wire-level", "control"]).unwrap();
        assert_groups_drawn(&wired, "phong+wire");
        let darker = img
            .pixels()
            .zip(wired.pixels())
            .filter(|(a, b)| a[0].max(a[1]).max(a[2]) > b[0].max(b[1]).max(b[2]) + 40)
            .count();
        assert!(darker > 100, "the wire darkens {darker} pixels");
        // --color none draws no group colours
        let plain = render(&path, &["--color", "none"]).unwrap();
        assert_eq!((count(&plain, 0), count(&plain, 1)), (0, 0));
    }
}
