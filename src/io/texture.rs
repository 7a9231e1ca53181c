//! Textures named by materials (PNG, JPEG, GIF), decoded within the read
//! budget: the image's size is read from its header first and checked
//! against `texture-pixels` before any pixel is decoded, and the decoder's
//! own allocation limit covers what the decoding and the conversion to
//! 8-bit RGBA take (at most 12 bytes a pixel, for 16-bit images). A small
//! file declaring a huge image (a decompression bomb) is refused before it
//! costs anything.

use super::limits::Budget;
use super::raw::format_err;
use crate::Result;
use crate::mesh::attributes::Texture;

/// Bytes a pixel may take while it is decoded and converted (a 16-bit RGBA
/// image, 8 bytes a pixel, converted to 4).
const BYTES_PER_PIXEL: u64 = 12;

/// The texture in the file `path` (named `at` in messages) that a model
/// names, read through its resolver and decoded within its budget; `None`
/// (with a warning) when it cannot be.
pub(crate) fn load(input: &super::Input, path: &std::path::Path, at: &str) -> Option<std::sync::Arc<Texture>> {
    let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let at = format!("{at} {}", crate::error::clean(&name, 40));
    let decoded = input.refs.read(path, None, &at).and_then(|bytes| decode(&bytes, input.budget, input.file, &at));
    match decoded {
        Ok(t) => Some(std::sync::Arc::new(t)),
        Err(e) => {
            input.warnings.warn("textures that cannot be read", format!("{e}; drawn without it"));
            None
        }
    }
}

/// The texture in the regular file `path`, read and decoded within
/// `budget` (messages name the file).
///
/// # Errors
/// Not a regular file, over the budget, or not an image the decoder reads.
pub fn load_file(path: &std::path::Path, budget: &Budget) -> Result<Texture> {
    let file = path.display().to_string();
    let bytes = super::resolve::read_regular(path, None, budget, &file, "texture")?;
    decode(&bytes, budget, &file, "texture")
}

/// Decodes the image `bytes` (named `at` in `file` for messages) into RGBA.
///
/// # Errors
/// An image over the `texture-pixels` limit, or one the decoder refuses,
/// naming the file and the image.
pub(crate) fn decode(bytes: &[u8], budget: &Budget, file: &str, at: &str) -> Result<Texture> {
    let err = |e: image::ImageError| format_err(file, at, e.to_string());
    let open = || image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format();
    let reader = open().map_err(|e| format_err(file, at, e.to_string()))?;
    if reader.format().is_none() {
        return Err(format_err(file, at, "not a PNG, JPEG or GIF image"));
    }
    let (w, h) = reader.into_dimensions().map_err(err)?;
    let pixels = u64::from(w) * u64::from(h);
    budget.check("texture-pixels", pixels, file, at)?;
    if pixels == 0 {
        return Err(format_err(file, at, "the image is empty"));
    }
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(w);
    limits.max_image_height = Some(h);
    limits.max_alloc = Some(pixels * BYTES_PER_PIXEL + (1 << 20));
    let mut reader = open().map_err(|e| format_err(file, at, e.to_string()))?;
    reader.limits(limits);
    let rgba = reader.decode().map_err(err)?.into_rgba8();
    Ok(Texture { width: rgba.width(), height: rgba.height(), rgba: rgba.into_raw() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::limits::Limits;

    /// A valid one-pixel PNG whose header then declares `w` by `h` (its
    /// data, one pixel, is far short of that: the decoder would fail late).
    fn png_declaring(w: u32, h: u32) -> Vec<u8> {
        let mut png = Vec::new();
        let img = image::RgbaImage::new(1, 1);
        img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
        // signature (8), IHDR length and type (8), then width and height
        png[16..20].copy_from_slice(&w.to_be_bytes());
        png[20..24].copy_from_slice(&h.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        png
    }

    fn crc32(b: &[u8]) -> u32 {
        let mut c = !0u32;
        for &x in b {
            c ^= u32::from(x);
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }

    #[test]
    fn a_huge_declared_image_is_refused_before_decoding() {
        let budget = Budget::new(Limits { texture_pixels: 1 << 20, ..Limits::for_memory(1 << 30) });
        let e = decode(&png_declaring(60_000, 60_000), &budget, "m.obj", "map_Kd bomb.png").unwrap_err().to_string();
        assert!(e.contains("texture-pixels limit"), "{e}");
    }

    #[test]
    fn a_small_image_decodes_to_rgba() {
        let mut img = image::RgbImage::new(2, 1);
        img.put_pixel(1, 0, image::Rgb([255, 0, 0]));
        let mut png = Vec::new();
        img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
        let t = decode(&png, &Budget::new(Limits::for_memory(1 << 30)), "m.obj", "t.png").unwrap();
        assert_eq!((t.width, t.height), (2, 1));
        assert_eq!(t.rgba, vec![0, 0, 0, 255, 255, 0, 0, 255]);
    }
}
