//! A small SVG writer (just the elements the plots use) and rasterization of an SVG to PNG
//! with resvg. Text is written as the outlines of the embedded typeface's glyphs (crate
//! `typeface`: DejaVu Sans), each line a path labelled with its text (`aria-label`), so that
//! an SVG shows the same type in every browser, editor and PDF converter, whatever fonts
//! they have, and its PNG is the same picture.

use anyhow::Context;
use std::fmt::Write;
pub use typeface::Weight;

/// Escapes text for XML content and attribute values.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Formats a coordinate compactly (4 decimals, trailing zeros trimmed).
pub fn f(v: f64) -> String {
    typeface::svg_number(v, 4)
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

    /// Text at (x, y) (baseline), `anchor` = start | middle | end, `size` the em size.
    pub fn text(&mut self, at: (f64, f64), size: f64, anchor: &str, style: &str, text: &str) {
        self.text_as(at, size, Weight::Regular, 0.0, anchor, style, text);
    }

    /// Text of a `weight`, turned by `rotate` degrees (clockwise, as SVG) about its anchor
    /// point at (x, y): the glyphs' outlines as one path.
    #[allow(clippy::too_many_arguments)]
    pub fn text_as(
        &mut self,
        (x, y): (f64, f64),
        size: f64,
        weight: Weight,
        rotate: f64,
        anchor: &str,
        style: &str,
        text: &str,
    ) {
        let line = typeface::Line::new(text, size as f32, weight);
        let shift = match anchor {
            "middle" => -0.5 * f64::from(line.advance),
            "end" => -f64::from(line.advance),
            _ => 0.0,
        };
        let label = escape(text);
        if rotate == 0.0 {
            let d = line.svg_path(x + shift, y);
            self.raw(&format!(r#"<path aria-label="{label}" d="{d}" {style}/>"#));
        } else {
            let d = line.svg_path(shift, 0.0);
            self.raw(&format!(
                r#"<path aria-label="{label}" transform="translate({},{}) rotate({})" d="{d}" {style}/>"#,
                f(x),
                f(y),
                f(rotate)
            ));
        }
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
    let opt = resvg::usvg::Options::default();
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
    fn text_is_outlined_labelled_and_rendered_without_fonts() {
        let mut s = Svg::new(120.0, 40.0);
        s.rect((0.0, 0.0), (120.0, 40.0), r#"fill="white""#);
        s.text((60.0, 28.0), 20.0, "middle", r#"fill="black""#, "a<b & c");
        let doc = s.finish("t");
        assert!(doc.contains(r#"aria-label="a&lt;b &amp; c""#), "{doc}");
        assert!(
            !doc.contains("<text"),
            "no text element: no font needed to show it"
        );
        let png = to_png(&doc, 1.0).unwrap();
        let img = image::load_from_memory(&png).unwrap().to_luma8();
        // Ink centred on x = 60: about as much left of it as right of it.
        let dark = |x0: u32, x1: u32| {
            (x0..x1)
                .flat_map(|x| (0..40).map(move |y| (x, y)))
                .filter(|&(x, y)| img.get_pixel(x, y).0[0] < 128)
                .count()
        };
        let (left, right) = (dark(0, 60), dark(60, 120));
        assert!(left > 40 && right > 40, "{left} {right}");
        assert!(left.abs_diff(right) * 3 < left + right, "{left} {right}");
        // Anti-aliased: grey edge pixels as well as black ones.
        assert!(img.pixels().any(|p| (64..192).contains(&p.0[0])));
    }

    #[test]
    fn rotated_and_bold_text_turn_about_their_anchor() {
        let mut s = Svg::new(40.0, 120.0);
        s.text_as(
            (20.0, 60.0),
            16.0,
            Weight::Bold,
            -90.0,
            "middle",
            "",
            "y / a",
        );
        let doc = s.finish("t");
        assert!(doc.contains("translate(20,60) rotate(-90)"), "{doc}");
        let regular = typeface::Line::new("y / a", 16.0, Weight::Regular).advance;
        let bold = typeface::Line::new("y / a", 16.0, Weight::Bold).advance;
        assert!(bold > regular);
    }
}
