//! The web page's address as the viewer's opening state:
//! `index.html?model=torus.obj&level=3&scheme=loop&shading=wire&backend=webgl2` (and
//! `adaptive=1`, `play=1`).

use super::ViewOptions;
use crate::render::Shading;
use crate::{Error, Result, Scheme};
use std::path::PathBuf;

/// What the page's address asks for: `?model=torus.obj&level=3&scheme=loop&shading=wire&backend=webgl2`.
#[derive(Debug, Default, PartialEq)]
pub(crate) struct PageQuery {
    /// A bundled model's file name (a URL is fetched by the page's script).
    pub(crate) model: Option<String>,
    pub(crate) level: Option<u32>,
    pub(crate) scheme: Option<Scheme>,
    pub(crate) shading: Option<Shading>,
    /// WebGL2 even where WebGPU is there.
    pub(crate) webgl2: bool,
    /// Start playing the animation.
    pub(crate) play: bool,
    /// Start with the adaptive display (the limit within half a pixel).
    pub(crate) adaptive: bool,
}

impl PageQuery {
    /// Reads `query` (`a=b&c=d`, with or without the `?`); unknown keys
    /// are ignored, bad values refused with the key named.
    pub(crate) fn parse(query: &str) -> Result<PageQuery> {
        let mut q = PageQuery::default();
        for pair in query.trim_start_matches('?').split('&').filter(|p| !p.is_empty()) {
            let (k, v) = pair.split_once('=').unwrap_or((pair, ""));
            let v = decode(v);
            let bad = |why: String| Error::Usage(format!("the page's address: {k}={v}: {why}"));
            match k {
                "model" => q.model = Some(v.clone()),
                "level" => q.level = Some(v.parse().map_err(|_| bad("not a level (0, 1, 2, ...)".into()))?),
                "scheme" => q.scheme = Some(v.parse().map_err(|e: String| bad(e))?),
                "shading" => q.shading = Some(v.parse().map_err(bad)?),
                "backend" => q.webgl2 = v.eq_ignore_ascii_case("webgl2") || v.eq_ignore_ascii_case("webgl"),
                "play" => q.play = v != "0" && v != "false",
                "adaptive" => q.adaptive = v != "0" && v != "false",
                _ => {}
            }
        }
        Ok(q)
    }

    /// A `model` that is neither a bundled model nor a URL (the page's
    /// script fetches what has a `/` or a scheme): said, not ignored.
    pub(crate) fn unknown_model(&self) -> Option<&str> {
        let m = self.model.as_deref()?;
        let url = m.contains('/') || m.contains(':');
        (!url && crate::bundled::model(m).is_none()).then_some(m)
    }

    /// The viewer's opening state: a bundled model by its name (others
    /// arrive as bytes), else the first launch's.
    pub(crate) fn view_options(&self) -> ViewOptions {
        let first = ViewOptions::first_launch();
        let bundled = self.model.as_deref().filter(|m| crate::bundled::model(m).is_some());
        let control = bundled.is_none() && self.model.is_none();
        ViewOptions {
            model: bundled.map(|m| PathBuf::from(format!("{}{m}", crate::bundled::PREFIX))),
            scheme: self.scheme.unwrap_or(if bundled.is_some() { Scheme::Loop } else { first.scheme }),
            level: self.level.unwrap_or(if bundled.is_some() { 2 } else { first.level }),
            control: control && first.control,
            play: self.play,
            adaptive: self.adaptive,
            ..ViewOptions::default()
        }
    }
}

/// `%xx` and `+` of a query value.
fn decode(v: &str) -> String {
    let b = v.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'+' => out.push(b' '),
            b'%' if i + 2 < b.len() => {
                match u8::from_str_radix(std::str::from_utf8(&b[i + 1..i + 3]).unwrap_or("zz"), 16) {
                    Ok(x) => {
                        out.push(x);
                        i += 2;
                    }
                    Err(_) => out.push(b'%'),
                }
            }
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_address_is_read_with_its_values_checked() {
        let q = PageQuery::parse("?model=torus.obj&level=3&scheme=loop&shading=wire&backend=webgl2").unwrap();
        assert_eq!(q.model.as_deref(), Some("torus.obj"));
        assert_eq!((q.level, q.scheme, q.shading, q.webgl2), (Some(3), Some(Scheme::Loop), Some(Shading::Wire), true));
        assert!(PageQuery::parse("level=x").unwrap_err().to_string().contains("level=x"));
        assert_eq!(decode("a%20b+c%2"), "a b c%2");
        let torus = q.view_options();
        assert_eq!(torus.model.as_deref(), Some(std::path::Path::new("bundled:torus.obj")));
        assert_eq!((torus.level, torus.scheme), (3, Scheme::Loop));
        let first = PageQuery::parse("").unwrap().view_options();
        assert_eq!((first.model, first.level, first.scheme), (None, 3, Scheme::Butterfly));
        let url = PageQuery::parse("model=https%3A%2F%2Fexample.org%2Fa.ply").unwrap();
        assert_eq!(url.model.as_deref(), Some("https://example.org/a.ply"));
        assert_eq!(url.view_options().model, None, "a URL arrives as bytes");
        assert_eq!(url.unknown_model(), None);
        assert_eq!(q.unknown_model(), None, "torus.obj is bundled");
        assert_eq!(PageQuery::parse("model=nope.obj").unwrap().unknown_model(), Some("nope.obj"));
        assert!(PageQuery::parse("adaptive=1").unwrap().view_options().adaptive);
        assert!(!PageQuery::parse("adaptive=0").unwrap().view_options().adaptive);
    }
}
