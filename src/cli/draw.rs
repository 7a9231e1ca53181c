//! The commands that draw offscreen: `render` (one PNG) and `animate` (a GIF
//! or numbered PNGs). Both need the `viewer` feature.

use super::args::{ColorArgs, InputArgs, SubdivArgs, parse_size};
use std::path::PathBuf;
use std::time::Instant;
use subdiv::anim::{Animation, Paths, Tweak};
use subdiv::mesh::Attributes;
use subdiv::{Error, Mesh, Result, bundled};

/// `subdiv render` arguments.
#[derive(clap::Args)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub struct RenderArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output PNG.
    output: PathBuf,
    #[command(flatten)]
    from: InputArgs,
    #[command(flatten)]
    sub: SubdivArgs,
    #[command(flatten)]
    color: ColorArgs,
    /// phong, flat, studio (matcap), wire, phong+wire, zebra (reflection
    /// lines) or isophotes.
    #[arg(long, default_value = "phong")]
    shading: String,
    /// Image size WxH.
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    size: (u32, u32),
    /// Orthographic projection.
    #[arg(long)]
    ortho: bool,
    /// Overlay the control mesh.
    #[arg(long)]
    control: bool,
    /// Draw the exact limit surface (Loop or Catmull-Clark), tessellated
    /// for this view within PX pixels of it (0.5 when no number follows),
    /// framed as level `-n` is: `subdiv tessellate` with a tolerance on
    /// the screen.
    #[arg(long, value_name = "PX", num_args = 0..=1, default_missing_value = "0.5")]
    adaptive: Option<f64>,
    #[command(flatten)]
    look: RenderLook,
    #[command(flatten)]
    inspect: RenderInspect,
}

/// The inspector's overlays of `render` (docs/viewer.md, Inspect).
#[derive(clap::Args)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub struct RenderInspect {
    /// Draw the operators of corner C of the level drawn as labelled arrows:
    /// n p o l r s u of the triangle table, or next prev twin swing of the
    /// quad table for catmull-clark and bilinear.
    #[arg(long, value_name = "C", conflicts_with = "stencil")]
    corner: Option<u32>,
    /// Draw the stencil of vertex V of the level drawn on the control mesh:
    /// each control vertex a disc sized by its weight's magnitude, coloured
    /// by its sign, with the weight beside it; the rules in the caption.
    #[arg(long, value_name = "V")]
    stencil: Option<u32>,
}

/// The wireframe and picture options of `render`.
#[derive(clap::Args)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub struct RenderLook {
    /// Wireframe edges drawn (with --shading wire or phong+wire): all, control
    /// (the control mesh's edges on the surface) or K (the edges made up to level K).
    #[arg(long, default_value = "all")]
    wire_level: String,
    /// Transparent background (alpha 0; the object stays opaque).
    #[arg(long)]
    transparent: bool,
    /// Render N times the size (lines N times as wide: the same picture, sharper).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=8))]
    scale: u32,
    /// Zebra and isophotes: the number of stripes.
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u8).range(2..=96))]
    stripes: u8,
    /// Zebra: the light bars' direction on the screen, degrees from vertical.
    #[arg(long, default_value_t = 0, allow_negative_numbers = true, value_parser = clap::value_parser!(i16).range(-180..=180))]
    stripe_angle: i16,
}

/// `subdiv animate` arguments.
#[derive(clap::Args)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub struct AnimateArgs {
    /// Model: a file or bundled:NAME (default: the bundled tetrahedron).
    #[arg(long)]
    model: Option<PathBuf>,
    /// Key paths (.paths; default: beside the model or in paths/, else generated loops).
    #[arg(long)]
    paths: Option<PathBuf>,
    #[command(flatten)]
    from: InputArgs,
    #[command(flatten)]
    sub: SubdivArgs,
    /// Colouring: none, shells (the level that made each vertex) or file (the model's vertex colours).
    #[arg(long, default_value = "none")]
    color: String,
    /// Path refinements n: K keys give K * 2^n frames.
    #[arg(long, default_value_t = 5)]
    refine: u32,
    /// Path tweak: bspline, four-point or jarek.
    #[arg(long, default_value = "jarek")]
    tweak: String,
    /// Write one looping GIF here.
    #[arg(long, conflicts_with = "frames_dir", required_unless_present_any = ["frames_dir", "stats"])]
    gif: Option<PathBuf>,
    /// Write frame_0000.png, ... into this directory.
    #[arg(long)]
    frames_dir: Option<PathBuf>,
    /// Image size WxH.
    #[arg(long, default_value = "480x480", value_parser = parse_size)]
    size: (u32, u32),
    /// phong, flat, studio (matcap), wire, phong+wire, zebra (reflection
    /// lines) or isophotes.
    #[arg(long, default_value = "phong")]
    shading: String,
    /// Overlay the moving control mesh.
    #[arg(long)]
    control: bool,
    /// Frames per second stored in the GIF.
    #[arg(long, default_value_t = 30.0)]
    fps: f32,
    /// Print plan_ms= (recording the plan) and frame_ms= (median per frame,
    /// positions and normals); without --gif/--frames-dir every frame is
    /// evaluated and nothing is written.
    #[arg(long)]
    stats: bool,
    /// Where the frames are evaluated, for the GIF, the PNG frames and --stats:
    /// cpu, or gpu (the stencil and normal compute passes, drawn straight from
    /// the buffers they write).
    #[arg(long, default_value = "cpu", value_parser = ["cpu", "gpu"])]
    eval: String,
}

impl AnimateArgs {
    /// `--stats` with no output file: time the frames, write nothing.
    fn stats_only(&self) -> bool {
        self.stats && self.gif.is_none() && self.frames_dir.is_none()
    }
}

/// The model and its default paths (beside it, bundled, or the tetrahedron's).
fn model(a: &AnimateArgs) -> Result<(Mesh, Attributes, Option<Paths>)> {
    let Some(m) = &a.model else {
        let (mesh, paths) = bundled::tetrahedron()?;
        return Ok((mesh, Attributes::default(), Some(paths)));
    };
    let loaded = a.from.read(m, true)?;
    let (mesh, attrs) = (loaded.mesh, loaded.attributes);
    let beside = match bundled::paths_for(m) {
        Some(src) => {
            let paths = src.load(&a.from.limits.limits()?)?;
            paths.check_model(&mesh, &src.describe())?;
            Some(paths)
        }
        None => None,
    };
    Ok((mesh, attrs, beside))
}

/// The model (with its crease-angle tags), its attributes, its paths and the
/// recorded animation of `subdiv animate`.
fn animation_of(a: &AnimateArgs) -> Result<(Mesh, Attributes, Paths, Animation)> {
    let tweak: Tweak = a.tweak.parse().map_err(Error::Usage)?;
    let level = a.sub.levels_or(5);
    let (mesh, attrs, default_paths) = model(a)?;
    let s = &a.sub.scheme.over(attrs.options);
    let mesh = s.features.apply(mesh);
    let paths = match (&a.paths, default_paths) {
        (Some(p), _) => {
            let paths = Paths::load(p, &a.from.limits.limits()?)?;
            paths.check_model(&mesh, &p.display().to_string())?;
            paths
        }
        (None, Some(paths)) => paths,
        (None, None) => Paths::generated(&mesh, 4),
    };
    let anim = Animation::new(&mesh, &paths, tweak, a.refine, s.scheme(), level, &s.options())?;
    Ok((mesh, attrs, paths, anim))
}

/// `subdiv animate --stats` without an output: evaluates every frame (at
/// least 32 evaluations, cycling) and prints the plan and per-frame times.
fn animate_stats(anim: &mut Animation) {
    let n = anim.frame_count().max(32);
    let (mut times, mut stencils, mut normals) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
    for f in 0..n {
        let t = Instant::now();
        std::hint::black_box(anim.evaluate(f).1.len());
        times.push(t.elapsed().as_secs_f64() * 1e3);
        stencils.push(anim.last_timing.0.as_secs_f64() * 1e3);
        normals.push(anim.last_timing.1.as_secs_f64() * 1e3);
    }
    let median = |t: &mut Vec<f64>| {
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    };
    println!(
        "plan_ms={:.3} frame_ms={:.3} frame_min_ms={:.3} (stencils_ms={:.3} normals_ms={:.3}) evaluations={n} frames={} triangles={} threads={}",
        anim.plan_ms(),
        median(&mut times),
        times[0],
        median(&mut stencils),
        median(&mut normals),
        anim.frame_count(),
        anim.topology().num_triangles(),
        rayon::current_num_threads()
    );
}

#[cfg(not(feature = "viewer"))]
pub(crate) fn render(_: &RenderArgs) -> Result<()> {
    Err(Error::Usage("built without the 'viewer' feature: rendering is not available".into()))
}

#[cfg(not(feature = "viewer"))]
pub(crate) fn animate(a: AnimateArgs) -> Result<()> {
    if a.eval == "gpu" {
        return Err(Error::Usage("built without the 'viewer' feature: no GPU evaluation".into()));
    }
    if a.stats_only() {
        animate_stats(&mut animation_of(&a)?.3);
        return Ok(());
    }
    Err(Error::Usage("built without the 'viewer' feature: animation export is not available".into()))
}

#[cfg(feature = "viewer")]
pub(crate) use gpu::{animate, render};

#[cfg(feature = "viewer")]
mod gpu {
    use super::super::progress;
    use super::{AnimateArgs, RenderArgs, RenderInspect, animate_stats, animation_of};
    use glam::Vec3;
    use subdiv::eval::color;
    use subdiv::eval::color::HalfWidth;
    use subdiv::mesh::Attributes;
    use subdiv::mesh::PolyMesh;
    use subdiv::mesh::colormap;
    use subdiv::mesh::{corner_ops, poly_corner_ops};
    use subdiv::render::Coloring;
    use subdiv::render::Paint;
    use subdiv::render::{
        Overlay, Viewport, paint_overlay, poly_corner_overlay, project_overlay, stencil_overlay,
        triangle_corner_overlay,
    };
    use subdiv::rules::stencil;
    use subdiv::rules::{creation_levels, displacement};
    use subdiv::{Error, Mesh, Result, Scheme};

    fn ramp(t: impl Iterator<Item = f32>) -> Vec<Vec3> {
        t.map(|t| Vec3::from(colormap(t))).collect()
    }

    /// The colours of the levels that made each vertex of a `levels`-deep refinement of `control`.
    fn shells(control: &Mesh, scheme: Scheme, levels: u32, nv: usize) -> Vec<Vec3> {
        let lv = creation_levels(control, scheme, levels, nv);
        ramp(lv.iter().map(|&l| f32::from(l) / levels.max(1) as f32))
    }

    /// What a curvature colouring's bar says: the curvature and the range in use.
    struct Legend {
        kind: subdiv::eval::color::CurvatureKind,
        scale: subdiv::eval::color::Scale,
    }

    /// The paint of a colouring for `fine`, `levels` levels of `scheme`
    /// over `control` (a curvature's with `isolines` per side of zero, over
    /// the range `range` or the default), and a curvature's legend; the
    /// file's attributes through `refiner`, the refiner `fine` came from
    /// (none: no levels, or no attributes).
    fn paint(
        (coloring, isolines, range): (Coloring, u8, Option<HalfWidth>),
        (control, fine): (&Mesh, &Mesh),
        attrs: &Attributes,
        refiner: Option<&subdiv::Refiner>,
        (scheme, levels, opts): (Scheme, u32, &subdiv::Options),
    ) -> Result<(Paint, Option<Legend>)> {
        // the attributes through the refiner that made the level (none: no
        // levels, or no attributes to carry)
        let refined = |a: Attributes| match refiner {
            Some(r) => r.attributes(&a),
            None => Ok(a),
        };
        let missing = |what: &str| Error::Usage(format!("--color {what}: the model has no {what}"));
        let paint = match coloring {
            Coloring::None => Paint::Material,
            Coloring::Shells => Paint::Colors(shells(control, scheme, levels, fine.positions.len())),
            Coloring::Displacement => {
                let d = displacement(control, fine, scheme, levels)?;
                let max = d.iter().fold(0.0f32, |a, &b| a.max(b));
                Paint::Colors(ramp(d.iter().map(|&x| if max > 0.0 { x / max } else { 0.0 })))
            }
            Coloring::File => {
                let Some(c) = attrs.colors.clone() else { return Err(missing("colors")) };
                let a = refined(Attributes { colors: Some(c), ..Default::default() })?;
                Paint::Colors(a.colors.ok_or_else(|| missing("colors"))?)
            }
            Coloring::Checker => {
                let Some(uv) = attrs.uv.clone() else { return Err(missing("texture coordinates")) };
                let a = refined(Attributes { uv: Some(uv), ..Default::default() })?;
                Paint::Checker(a.uv.ok_or_else(|| missing("texture coordinates"))?)
            }
            Coloring::Material => {
                let Some(m) = attrs.materials.clone() else { return Err(missing("materials (usemtl)")) };
                let a = refined(Attributes { uv: attrs.uv.clone(), materials: Some(m), ..Default::default() })?;
                let groups = a.materials.ok_or_else(|| missing("materials (usemtl)"))?;
                Paint::Materials { groups, uv: a.uv }
            }
            Coloring::Curvature(kind) => {
                color::check_scheme(scheme).map_err(|e| Error::Usage(format!("--color {}: {e}", kind.name())))?;
                let values = color::vertex_curvatures(control, fine, (scheme, levels, opts), kind)?;
                let scale = color::Scale::choose(range, &values, &fine.ct, &fine.positions);
                let t = color::normalized(&values, scale.half);
                return Ok((Paint::Values { t, isolines }, Some(Legend { kind, scale })));
            }
        };
        Ok((paint, None))
    }

    /// `subdiv render`.
    pub(crate) fn render(a: &RenderArgs) -> Result<()> {
        let shading: subdiv::render::Shading = a.shading.parse().map_err(Error::Usage)?;
        let levels = a.sub.levels_or(0);
        let asked = a.color.asked()?;
        let isolines = a.color.isolines(asked)?.unwrap_or(0);
        let range = a.color.range(asked)?;
        // textures decoded: the materials are drawn
        let loaded = a.from.read(&a.input, true)?;
        let (mesh, attrs) = (loaded.mesh, loaded.attributes);
        let s = &a.sub.scheme.over(attrs.options);
        let coloring = Coloring::initial(asked, attrs.materials.is_some());
        let mesh = s.features.apply(mesh);
        // the file's attributes, where the paint draws them, ride on the
        // refiner that makes the level
        let painted = matches!(coloring, Coloring::File | Coloring::Checker | Coloring::Material);
        let (fine, refiner) = match painted && !attrs.is_empty() && levels > 0 {
            true => {
                let r = subdiv::Refiner::new(&mesh, s.scheme(), levels, &s.options())?;
                (r.mesh(), Some(r))
            }
            false => (subdiv::subdivide(&mesh, s.scheme(), levels, &s.options())?.0, None),
        };
        let how = (s.scheme(), levels, &s.options());
        let (paint, legend) = paint((coloring, isolines, range), (&mesh, &fine), &attrs, refiner.as_ref(), how)?;
        let (width, height) = a.size;
        let wire_edges = a.look.wire_level.parse().map_err(Error::Usage)?;
        let shot = subdiv::render::Shot { scale: a.look.scale, transparent: a.look.transparent };
        let stripes = subdiv::render::Stripes { count: a.look.stripes, angle: a.look.stripe_angle };
        let opts =
            subdiv::render::RenderOptions { shading, width, height, orthographic: a.ortho, wire_edges, shot, stripes };
        let overlay = inspect_overlay(&a.inspect, &mesh, &fine, (s.scheme(), levels, &s.options()))?;
        // a stencil is drawn on the cage: the control mesh is shown with it
        let control = (a.control || a.inspect.stencil.is_some()).then_some(&mesh);
        let mut img = match a.adaptive {
            Some(_) if !matches!(paint, Paint::Material) || overlay.is_some() => {
                return Err(Error::Usage(
                    "--adaptive draws the surface in its material: no --color, --corner or --stencil with it".into(),
                ));
            }
            Some(pixels) => render_adaptive((&mesh, &fine, control), (s.scheme(), &s.options()), pixels, &opts)?,
            None => subdiv::render::render_image_painted(&fine, control, &opts, &paint)?,
        };
        if let Some(Legend { kind, scale }) = legend {
            subdiv::render::draw_colorbar(&mut img, scale.half, isolines, &[kind.words().into(), scale.describe()]);
        }
        if let Some(overlay) = overlay {
            let camera = subdiv::render::default_camera(control.unwrap_or(&fine), &opts);
            let k = opts.shot.scale as f32;
            let vp = Viewport::image(img.width(), img.height(), k);
            paint_overlay(&mut img, &project_overlay(&overlay, &camera, &vp, 10.0), k);
        }
        subdiv::render::save_png(&img, &a.output)
    }

    /// The limit surface of `mesh` under `how`, tessellated within `pixels`
    /// on the screen of the view that frames `fine` (or `control`, drawn
    /// over it) and drawn with its exact normals.
    fn render_adaptive(
        (mesh, fine, control): (&Mesh, &Mesh, Option<&Mesh>),
        (scheme, options): (Scheme, &subdiv::Options),
        pixels: f64,
        opts: &subdiv::render::RenderOptions,
    ) -> Result<image::RgbaImage> {
        let camera = subdiv::render::default_camera(control.unwrap_or(fine), opts);
        let (w, h) = opts.shot.size(opts.width, opts.height);
        let view_proj = camera.view_proj(opts.width as f32 / opts.height.max(1) as f32).as_dmat4();
        let view = subdiv::ScreenTolerance { view_proj, width: f64::from(w), height: f64::from(h), pixels };
        let points: Vec<glam::DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let t = subdiv::tessellate(mesh, &points, scheme, options, subdiv::Tolerance::Screen(view))?;
        let s = &t.stats;
        log::info!(
            "adaptive: {} triangles, largest distance measured {:.3} px of {pixels} px, {} rounds, {:.1} ms",
            t.triangles.len(),
            s.worst,
            s.rounds,
            s.seconds * 1e3
        );
        let positions = t.positions.iter().map(|p| p.as_vec3()).collect();
        let corners: Vec<u32> = t.triangles.iter().flatten().copied().collect();
        let drawn = Mesh::from_triangles(positions, &corners).map_err(|e| Error::Usage(e.to_string()))?;
        let normals: Vec<Vec3> = t.normals.iter().map(|n| n.as_vec3()).collect();
        let mut off = subdiv::render::Offscreen::new(w, h)?;
        off.set_shot(opts.shot);
        let gm = subdiv::render::GpuMesh::new(&off.gpu.device, &drawn.ct, &drawn.positions, &normals)?;
        let gc = control.map(|c| off.upload(c)).transpose()?;
        let look = subdiv::render::Look {
            control: control.is_some(),
            wire_edges: opts.wire_edges,
            stripes: opts.stripes,
            ..opts.shading.look()
        };
        off.render_one(camera, &gm, gc.as_ref(), look)
    }

    /// The overlay of `--corner` or `--stencil` on `fine`, level `levels` of
    /// `scheme` over `control`; a corner or vertex out of range is refused.
    fn inspect_overlay(
        a: &RenderInspect,
        control: &Mesh,
        fine: &Mesh,
        (scheme, levels, opts): (Scheme, u32, &subdiv::Options),
    ) -> Result<Option<Overlay>> {
        let shown = format!("level {levels} of {scheme}");
        if let Some(v) = a.stencil {
            let st = stencil(control, scheme, levels, opts, v)?;
            return Ok(Some(stencil_overlay(&control.positions, &st, fine.positions[v as usize])));
        }
        let Some(c) = a.corner else { return Ok(None) };
        let out_of_range = |n: usize| Error::Usage(format!("corner {c} out of range: {shown} has {n} corners"));
        let mut overlay = if scheme.is_polygonal() {
            let pm = PolyMesh::from_mesh(fine);
            let x = poly_corner_ops(&pm.pt, c).ok_or_else(|| out_of_range(pm.pt.num_corners()))?;
            poly_corner_overlay(&pm.pt, &fine.positions, &x)
        } else {
            let x = corner_ops(&fine.ct, c).ok_or_else(|| out_of_range(fine.ct.num_corners()))?;
            triangle_corner_overlay(fine.ct.v_table(), &fine.positions, &x)
        };
        let table = if scheme.is_polygonal() { "quad table" } else { "triangle table" };
        overlay.caption.insert(0, format!("{shown}, the {table}"));
        Ok(Some(overlay))
    }

    /// `subdiv animate --stats --eval gpu`: every frame through the compute passes.
    fn animate_stats_gpu(anim: &subdiv::anim::Animation) -> Result<()> {
        let n = anim.frame_count().max(32);
        let (mut times, upload_ms, adapter) = subdiv::render::time_frames(anim, n)?;
        times.sort_by(f64::total_cmp);
        println!(
            "plan_ms={:.3} frame_ms={:.3} frame_min_ms={:.3} (gpu upload_ms={upload_ms:.3}) evaluations={n} frames={} triangles={} adapter=\"{adapter}\"",
            anim.plan_ms(),
            times[n / 2],
            times[0],
            anim.frame_count(),
            anim.topology().num_triangles(),
        );
        Ok(())
    }

    /// `subdiv animate`.
    pub(crate) fn animate(a: AnimateArgs) -> Result<()> {
        use subdiv::render::{Evaluation, ExportStyle, ExportTarget, export_animation};
        let shading: subdiv::render::Shading = a.shading.parse().map_err(Error::Usage)?;
        let coloring: Coloring = a.color.parse().map_err(Error::Usage)?;
        let (s, level) = (&a.sub.scheme, a.sub.levels_or(5));
        let (mesh, attrs, paths, mut anim) = animation_of(&a)?;
        if a.stats_only() {
            if a.eval == "gpu" {
                return animate_stats_gpu(&anim);
            }
            animate_stats(&mut anim);
            return Ok(());
        }
        let nv = anim.topology().num_vertices();
        let colors = match coloring {
            Coloring::None => None,
            Coloring::Shells => Some(shells(&mesh, s.scheme(), level, nv)),
            Coloring::File => {
                // through the animation's own plan: the colours in its finest
                // level's (locality) order, no second refinement
                let colors = attrs.colors.filter(|c| c.len() == mesh.positions.len());
                let colors = colors.ok_or_else(|| Error::Usage("--color file: the model has no colors".into()))?;
                let mut fine = Vec::new();
                anim.plan().apply(&colors, &mut subdiv::rules::PlanScratch::default(), &mut fine);
                Some(fine.into_iter().map(|c| c.clamp(glam::Vec3::ZERO, glam::Vec3::ONE)).collect())
            }
            other => return Err(Error::Usage(format!("animate --color {}: use none, shells or file", other.name()))),
        };
        let target = match (a.gif, a.frames_dir) {
            (Some(g), _) => ExportTarget::Gif(g),
            (None, Some(d)) => ExportTarget::Frames(d),
            (None, None) => return Err(Error::Usage("give --gif FILE or --frames-dir DIR".into())),
        };
        let look = subdiv::render::Look { control: a.control, ..shading.look() };
        let eval = if a.eval == "gpu" { Evaluation::Gpu } else { Evaluation::Cpu };
        let style = ExportStyle { size: a.size, look, fps: a.fps, eval };
        let t0 = std::time::Instant::now();
        let total = anim.frame_count();
        let bar = progress::bar(total as u64, "frames");
        let n = export_animation(&mut anim, &mesh, &target, &style, colors.as_deref(), |d, _| {
            bar.set_position(d as u64);
            true
        })?;
        bar.finish_and_clear();
        let out = match &target {
            ExportTarget::Gif(p) | ExportTarget::Frames(p) => p.display().to_string(),
        };
        println!(
            "wrote {n} frames ({} keys x 2^{}, {} triangles each, evaluated on the {}) to {out} in {:.2} s",
            paths.keys_per_vertex,
            a.refine,
            anim.topology().num_triangles(),
            a.eval.to_uppercase(),
            t0.elapsed().as_secs_f64()
        );
        match (a.stats, eval) {
            // the median of the last 64 evaluations (the export's)
            (true, Evaluation::Cpu) => {
                println!("plan_ms={:.3} frame_ms={:.3}", anim.plan_ms(), anim.frame_ms().unwrap_or(0.0))
            }
            // no frame was evaluated on the CPU; --stats without an output times the GPU's
            (true, Evaluation::Gpu) => println!("plan_ms={:.3}", anim.plan_ms()),
            (false, _) => {}
        }
        Ok(())
    }
}
