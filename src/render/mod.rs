//! The wgpu renderer: one set of pipelines (shaders/mesh.wgsl) used by the
//! window and by offscreen rendering to PNG.
//!
//! Data in: flat position/normal arrays and the corner table's V table; the
//! mesh core knows nothing of this module.

pub(crate) mod blit;
pub(crate) mod camera;
pub(crate) mod colorbar;
pub(crate) mod coloring;
pub(crate) mod export;
pub(crate) mod gpu;
pub(crate) mod gpu_anim;
pub(crate) mod gpu_mesh;
pub(crate) mod inspect;
pub(crate) mod materials;
pub(crate) mod offscreen;
pub(crate) mod overlay;
pub(crate) mod pipelines;
pub(crate) mod readback;
pub(crate) mod scene;
pub(crate) mod textures;

// What the library's users reach; the modules are the crate's own.
pub use camera::Camera;
pub use colorbar::draw as draw_colorbar;
pub use coloring::Coloring;
pub use export::{Evaluation, ExportStyle, ExportTarget, export_animation, frame_path, motion_bounds};
pub use gpu::Gpu;
pub use gpu_anim::{GpuAnimator, time_frames};
pub use gpu_mesh::GpuMesh;
pub use inspect::{
    op_color, poly_corner_overlay, polygon_corner_point, stencil_overlay, triangle_corner_overlay,
    triangle_corner_point, weight_color,
};
pub use materials::sample as sample_material;
pub use offscreen::{Offscreen, shoot};
pub use overlay::{Overlay, Prim, Viewport, paint as paint_overlay, project as project_overlay};
pub use scene::{
    FILL_INTENSITY, FILL_LIGHT, FRONT, HEADLIGHT_INTENSITY, KEY_INTENSITY, KEY_LIGHT, Renderer, Targets, ViewportDraw,
    background_srgb8_at,
};
pub use textures::MaterialDraw;

use crate::{Error, Mesh, Result};
use std::path::Path;

/// Depth buffer format of every pass.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// How the faces are filled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Surface {
    /// Smooth Phong shading with interpolated vertex normals.
    #[default]
    Smooth,
    /// Flat shading, one normal per face.
    Flat,
    /// Studio: a procedural matcap (clay under a soft key light, a sky
    /// above and a rim), from the normal in view space, so the light turns
    /// with the camera and every side reads alike.
    Studio,
    /// Faces not drawn (they still hide the lines behind them when the wireframe is on).
    Hidden,
    /// Reflection lines (zebra): the mirror image of parallel light bars
    /// fixed to the camera, from the normal per pixel ([`Stripes`]), so a
    /// break in tangent continuity shows as a jump in the stripes and one in
    /// curvature as a kink.
    Zebra,
    /// Isophotes: bands of equal angle between the normal and the view
    /// direction ([`Stripes`] sets their count).
    Isophotes,
}

/// The stripes of [`Surface::Zebra`] and [`Surface::Isophotes`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stripes {
    /// Zebra: light bars in the ring around the object the surface
    /// mirrors; isophotes: bands from facing the eye to grazing.
    pub count: u8,
    /// Direction of the light bars on the screen, in degrees from vertical.
    pub angle: i16,
}

impl Default for Stripes {
    fn default() -> Self {
        Stripes { count: 16, angle: 0 }
    }
}

/// What one viewport shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Look {
    /// Face fill.
    pub surface: Surface,
    /// Edges as lines.
    pub wireframe: bool,
    /// Control mesh edges overlaid.
    pub control: bool,
    /// Vertex normals as short segments.
    pub normals: bool,
    /// Per-vertex colours instead of the material colour (when the mesh has them).
    pub colors: bool,
    /// The colour attribute holds texture coordinates: show a checker texture.
    pub uv_checker: bool,
    /// The material groups of a mesh that has them ([`GpuMesh::textured`]):
    /// each group's colour times its texture, sampled per pixel.
    pub materials: bool,
    /// Sharp edges (creases) drawn in their own colour.
    pub sharp: bool,
    /// Which edges the wireframe draws, by generation.
    pub wire_edges: WireEdges,
    /// The stripes of the zebra and isophote surfaces.
    pub stripes: Stripes,
    /// The colour attribute holds values on the curvature colours' diverging
    /// map (see `GpuMesh::set_values`), coloured per pixel.
    pub values: bool,
    /// With `values`: contour lines of the value at zero (wider and darker)
    /// and at `isolines` levels on each side, every multiple of
    /// `1 / (isolines + 1)` of the colour range's half-width short of its
    /// ends; 0 draws none.
    pub isolines: u8,
}

/// The edges a wireframe draws, by the level at which each was made (see
/// [`crate::mesh::Generations`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum WireEdges {
    /// Every edge of the mesh.
    #[default]
    All,
    /// The edges made up to this level: 0 draws only the pieces of the
    /// control mesh's edges (its curves on the smooth surface).
    UpTo(u8),
}

impl WireEdges {
    /// The highest generation drawn.
    pub(crate) fn max_generation(self) -> u8 {
        match self {
            WireEdges::All => u8::MAX,
            WireEdges::UpTo(k) => k,
        }
    }
}

impl std::str::FromStr for WireEdges {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "all" => Ok(WireEdges::All),
            "control" => Ok(WireEdges::UpTo(0)),
            _ => s
                .parse::<u8>()
                .map(WireEdges::UpTo)
                .map_err(|_| format!("unknown wire level '{s}' (expected all, control or a level 0..=255)")),
        }
    }
}

/// Shading modes of the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    /// Smooth Phong.
    #[default]
    Phong,
    /// Flat (one normal per face).
    Flat,
    /// Studio matcap.
    Studio,
    /// Wireframe only (hidden lines removed).
    Wire,
    /// Phong with the wireframe over it.
    PhongWire,
    /// Reflection lines ([`Surface::Zebra`]).
    Zebra,
    /// Isophotes ([`Surface::Isophotes`]).
    Isophotes,
}

impl Shading {
    /// The viewport look for this mode.
    pub fn look(self) -> Look {
        let (surface, wireframe) = match self {
            Shading::Phong => (Surface::Smooth, false),
            Shading::Flat => (Surface::Flat, false),
            Shading::Studio => (Surface::Studio, false),
            Shading::Wire => (Surface::Hidden, true),
            Shading::PhongWire => (Surface::Smooth, true),
            Shading::Zebra => (Surface::Zebra, false),
            Shading::Isophotes => (Surface::Isophotes, false),
        };
        Look { surface, wireframe, ..Look::default() }
    }
}

impl std::str::FromStr for Shading {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "phong" | "smooth" => Ok(Shading::Phong),
            "flat" => Ok(Shading::Flat),
            "studio" | "matcap" => Ok(Shading::Studio),
            "wire" | "wireframe" => Ok(Shading::Wire),
            "phong+wire" | "phong-wire" => Ok(Shading::PhongWire),
            "zebra" | "reflection-lines" => Ok(Shading::Zebra),
            "isophotes" => Ok(Shading::Isophotes),
            _ => Err(format!(
                "unknown shading '{s}' (expected phong, flat, studio, wire, phong+wire, zebra or isophotes)"
            )),
        }
    }
}

/// Options of an offscreen render.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Shading mode.
    pub shading: Shading,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Orthographic instead of perspective projection.
    pub orthographic: bool,
    /// Which edges the wireframe draws.
    pub wire_edges: WireEdges,
    /// How the image is taken (transparent background, scale).
    pub shot: Shot,
    /// The stripes of the zebra and isophote shadings.
    pub stripes: Stripes,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            shading: Shading::Phong,
            width: 800,
            height: 600,
            orthographic: false,
            wire_edges: WireEdges::All,
            shot: Shot::default(),
            stripes: Stripes::default(),
        }
    }
}

/// How a picture is taken: the image is `scale` times the size asked for
/// (lines `scale` times as wide, so it looks the same, only sharper), on a
/// transparent background (alpha 0, the object opaque) when `transparent`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shot {
    /// Pixels per requested pixel, 1 or more.
    pub scale: u32,
    /// Alpha 0 where nothing is drawn.
    pub transparent: bool,
}

impl Default for Shot {
    fn default() -> Self {
        Shot { scale: 1, transparent: false }
    }
}

impl Shot {
    /// The image size of a `width` x `height` view.
    pub fn size(self, width: u32, height: u32) -> (u32, u32) {
        let k = self.scale.max(1);
        (width.saturating_mul(k), height.saturating_mul(k))
    }
}

/// The camera an offscreen render uses: the default direction, fitted to
/// the vertices of `frame` (the control mesh, so every level is framed
/// alike; a limit surface lies inside its control mesh's hull).
pub fn default_camera(frame: &Mesh, opts: &RenderOptions) -> Camera {
    Camera::framing_points(&frame.positions, opts.width as f32 / opts.height.max(1) as f32, opts.orthographic)
}

/// Renders `mesh` (with `control`'s edges overlaid when given) to an image.
///
/// # Errors
/// [`Error::Gpu`] without an adapter; size errors.
pub fn render_image(mesh: &Mesh, control: Option<&Mesh>, opts: &RenderOptions) -> Result<image::RgbaImage> {
    render_image_painted(mesh, control, opts, &Paint::Material)
}

/// What colours the faces of an offscreen render besides the material.
#[derive(Clone, Debug, Default)]
pub enum Paint {
    /// The material colour.
    #[default]
    Material,
    /// Linear RGB colours, one per vertex.
    Colors(Vec<glam::Vec3>),
    /// Values on the diverging map of the curvature colours, one per
    /// vertex: each value over the range's half-width (NaN: not evaluated,
    /// grey), coloured per pixel, with `isolines` contour lines per side of
    /// zero (see [`Look::isolines`]).
    Values {
        /// Value over the range's half-width per vertex.
        t: Vec<f32>,
        /// Contour lines per side of zero; 0 draws none.
        isolines: u8,
    },
    /// A checker through texture coordinates, one per corner.
    Checker(Vec<glam::Vec2>),
    /// The material groups (one material per triangle), each drawn in its
    /// colour times its texture sampled per pixel through the texture
    /// coordinates (one per corner; without them the flat colours).
    Materials {
        /// The groups, their materials and decoded textures.
        groups: crate::mesh::attributes::MaterialGroups,
        /// Texture coordinates, one per corner.
        uv: Option<Vec<glam::Vec2>>,
    },
}

/// [`render_image`] with the faces painted by `paint`.
///
/// # Errors
/// As [`render_image`].
pub fn render_image_painted(
    mesh: &Mesh,
    control: Option<&Mesh>,
    opts: &RenderOptions,
    paint: &Paint,
) -> Result<image::RgbaImage> {
    let (w, h) = opts.shot.size(opts.width, opts.height);
    let mut off = Offscreen::new(w, h)?;
    off.set_shot(opts.shot);
    let mut look =
        Look { control: control.is_some(), wire_edges: opts.wire_edges, stripes: opts.stripes, ..opts.shading.look() };
    let gm = match paint {
        Paint::Material => off.upload(mesh)?,
        Paint::Colors(c) => {
            let mut gm = off.upload(mesh)?;
            gm.set_colors(&off.gpu.device, c);
            look.colors = true;
            gm
        }
        Paint::Values { t, isolines } => {
            let mut gm = off.upload(mesh)?;
            gm.set_values(&off.gpu.device, t);
            (look.colors, look.values, look.isolines) = (true, true, *isolines);
            gm
        }
        Paint::Checker(uv) => {
            let attr: Vec<glam::Vec3> = uv.iter().map(|t| t.extend(0.0)).collect();
            (look.colors, look.uv_checker) = (true, true);
            GpuMesh::unwelded(&off.gpu.device, &mesh.ct, &mesh.positions, &mesh.vertex_normals(), &attr)?
        }
        Paint::Materials { groups, uv } => {
            look.materials = true;
            let (device, queue, normals) = (&off.gpu.device, &off.gpu.queue, mesh.vertex_normals());
            let materials = textures::MaterialDraw { groups, uv: uv.as_deref(), reuse: None };
            GpuMesh::textured(device, queue, &mesh.ct, &mesh.positions, &normals, materials)?
        }
    };
    let gc = control.map(|c| off.upload(c)).transpose()?;
    off.render_one(default_camera(control.unwrap_or(mesh), opts), &gm, gc.as_ref(), look)
}

/// Writes an image as PNG through a temporary file and a rename.
///
/// # Errors
/// I/O or encoding errors, naming the file.
pub fn save_png(img: &image::RgbaImage, out: &Path) -> Result<()> {
    crate::io::atomic_write(out, |w| {
        let enc = image::codecs::png::PngEncoder::new(w);
        image::ImageEncoder::write_image(enc, img.as_raw(), img.width(), img.height(), image::ExtendedColorType::Rgba8)
            .map_err(|e| Error::encode(out, "PNG", e))
    })
}
