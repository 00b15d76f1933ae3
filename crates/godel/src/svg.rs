//! A small SVG writer (just the elements the plots use) and rasterization of an SVG to PNG
//! with resvg, using the DejaVu Sans font embedded in the binary (assets/fonts, see
//! assets/NOTICE.md), so that PNG text looks the same on every machine.

use anyhow::Context;
use std::fmt::Write;

/// The embedded font; SVG text should ask for [`FONT_FAMILY`].
const DEJAVU_SANS: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
/// The CSS font list used in the SVGs: DejaVu Sans first (embedded for PNG), then fallbacks.
pub const FONT_FAMILY: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

/// Escapes text for XML content and attribute values.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Formats a coordinate compactly (4 decimals, trailing zeros trimmed).
pub fn f(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// An SVG document under construction; elements are appended as text.
pub struct Svg {
    width: f64,
    height: f64,
    body: String,
}

impl Svg {
    pub fn new(width: f64, height: f64) -> Svg {
        Svg {
            width,
            height,
            body: String::new(),
        }
    }

    /// Appends a raw element (already valid SVG).
    pub fn raw(&mut self, element: &str) {
        self.body.push_str(element);
        self.body.push('\n');
    }

    /// Opens a group with the given attributes (e.g. `transform="..."`); close with [`Svg::end_group`].
    pub fn group(&mut self, attrs: &str) {
        self.raw(&format!("<g {attrs}>"));
    }

    pub fn end_group(&mut self) {
        self.raw("</g>");
    }

    pub fn line(&mut self, (x1, y1): (f64, f64), (x2, y2): (f64, f64), style: &str) {
        self.raw(&format!(
            r#"<line x1="{}" y1="{}" x2="{}" y2="{}" {style}/>"#,
            f(x1),
            f(y1),
            f(x2),
            f(y2)
        ));
    }

    pub fn polyline(&mut self, points: &[(f64, f64)], style: &str) {
        let mut p = String::new();
        for (i, (x, y)) in points.iter().enumerate() {
            let _ = write!(p, "{}{},{}", if i == 0 { "" } else { " " }, f(*x), f(*y));
        }
        self.raw(&format!(r#"<polyline fill="none" points="{p}" {style}/>"#));
    }

    pub fn polygon(&mut self, points: &[(f64, f64)], style: &str) {
        let p: Vec<String> = points
            .iter()
            .map(|(x, y)| format!("{},{}", f(*x), f(*y)))
            .collect();
        self.raw(&format!(r#"<polygon points="{}" {style}/>"#, p.join(" ")));
    }

    pub fn circle(&mut self, (cx, cy): (f64, f64), r: f64, style: &str) {
        self.raw(&format!(
            r#"<circle cx="{}" cy="{}" r="{}" {style}/>"#,
            f(cx),
            f(cy),
            f(r)
        ));
    }

    pub fn rect(&mut self, (x, y): (f64, f64), (w, h): (f64, f64), style: &str) {
        self.raw(&format!(
            r#"<rect x="{}" y="{}" width="{}" height="{}" {style}/>"#,
            f(x),
            f(y),
            f(w),
            f(h)
        ));
    }

    /// Text at (x, y) (baseline), `anchor` = start | middle | end.
    pub fn text(&mut self, (x, y): (f64, f64), size: f64, anchor: &str, style: &str, text: &str) {
        self.raw(&format!(
            r#"<text x="{}" y="{}" font-family="{FONT_FAMILY}" font-size="{}" text-anchor="{anchor}" {style}>{}</text>"#,
            f(x),
            f(y),
            f(size),
            escape(text)
        ));
    }

    /// The complete document.
    pub fn finish(self, title: &str) -> String {
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
             <svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n\
             <title>{t}</title>\n{body}</svg>\n",
            w = f(self.width),
            h = f(self.height),
            t = escape(title),
            body = self.body
        )
    }
}

/// Rasterizes an SVG document to PNG bytes at `scale` pixels per SVG unit.
pub fn to_png(svg: &str, scale: f32) -> anyhow::Result<Vec<u8>> {
    let mut opt = resvg::usvg::Options::default();
    {
        let db = opt.fontdb_mut();
        db.load_font_data(DEJAVU_SANS.to_vec());
        db.set_sans_serif_family("DejaVu Sans");
    }
    opt.font_family = "DejaVu Sans".to_string();
    let tree = resvg::usvg::Tree::from_str(svg, &opt).context("parsing the generated SVG")?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(scale)
        .context("image size")?;
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height())
        .context("allocating the image")?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().context("encoding PNG")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_compact() {
        assert_eq!(f(1.0), "1");
        assert_eq!(f(-0.00001), "0");
        assert_eq!(f(2.50004), "2.5");
        assert_eq!(f(-1.23456), "-1.2346");
    }

    #[test]
    fn text_is_escaped_and_png_renders() {
        let mut s = Svg::new(40.0, 20.0);
        s.rect((0.0, 0.0), (40.0, 20.0), r#"fill="white""#);
        s.text((2.0, 15.0), 12.0, "start", "", "a<b & c");
        let doc = s.finish("t");
        assert!(doc.contains("a&lt;b &amp; c"));
        let png = to_png(&doc, 1.0).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
}
