//! The SVG writer every picture and chart uses: the document header (size, view box, font,
//! white background), `fmt::Write` for the body, and the one XML escaper.

use std::fmt;

/// Escapes text for an SVG text node or a double- or single-quoted attribute value: `&`, `<`,
/// `>`, `"` and `'`.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// A page for plane figures (y up): the points' bounding box scaled to `size` pixels across its
/// longer side, a 20-pixel margin, and a 24-pixel caption line below.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    x0: f64,
    y1: f64,
    /// Pixels per unit.
    pub scale: f64,
    /// The margin (pixels).
    pub margin: f64,
    /// The page's width (pixels).
    pub width: f64,
    /// The page's height (pixels), caption line included.
    pub height: f64,
}

impl Fit {
    /// The page for `points` (the unit square when there are none).
    pub fn new<'a>(points: impl IntoIterator<Item = &'a [f64; 2]>, size: f64) -> Fit {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for p in points {
            (x0, x1, y0, y1) = (x0.min(p[0]), x1.max(p[0]), y0.min(p[1]), y1.max(p[1]));
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        let margin = 20.0;
        let scale = size / (x1 - x0).max(y1 - y0).max(1e-9);
        let (width, height) = ((x1 - x0) * scale + 2.0 * margin, (y1 - y0) * scale + 2.0 * margin + 24.0);
        Fit { x0, y1, scale, margin, width, height }
    }

    /// A point's position on the page.
    pub fn tx(&self, p: [f64; 2]) -> (f64, f64) {
        (self.margin + (p[0] - self.x0) * self.scale, self.margin + (self.y1 - p[1]) * self.scale)
    }
}

/// An SVG document being written: [`Svg::new`] writes the header and a white background; the
/// body is written with `write!`/`writeln!` (escape text with [`escape`]); [`Svg::finish`]
/// closes the document.
pub struct Svg {
    out: String,
}

impl Svg {
    /// A `width × height` document (user units = pixels) in DejaVu Sans, with `font_size` as the
    /// default text size when given.
    pub fn new(width: f64, height: f64, font_size: Option<f64>) -> Svg {
        let mut out = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.1} {height:.1}" font-family="DejaVu Sans, sans-serif""#
        );
        if let Some(size) = font_size {
            out.push_str(&format!(r#" font-size="{size}""#));
        }
        out.push_str(">\n");
        out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
        Svg { out }
    }

    /// Like [`Svg::new`], with a `<defs>` section (patterns, markers) right after the header.
    pub fn with_defs(width: f64, height: f64, font_size: Option<f64>, defs: &str) -> Svg {
        let mut s = Svg::new(width, height, font_size);
        let background = "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
        let at = s.out.len() - background.len();
        s.out.insert_str(at, &format!("<defs>\n{defs}</defs>\n"));
        s
    }

    /// Appends a text element at `(x, y)` with extra attributes (`attrs`, written as given) and
    /// `content` escaped.
    pub fn text(&mut self, x: f64, y: f64, attrs: &str, content: &str) {
        let sep = if attrs.is_empty() { "" } else { " " };
        self.out.push_str(&format!("<text x=\"{x:.1}\" y=\"{y:.1}\"{sep}{attrs}>{}</text>\n", escape(content)));
    }

    /// Closes the document and returns its text.
    pub fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }
}

impl fmt::Write for Svg {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.out.push_str(s);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_and_both_quotes() {
        assert_eq!(escape(r#"a<b>&"c"'d'"#), "a&lt;b&gt;&amp;&quot;c&quot;&apos;d&apos;");
        assert_eq!(escape("plain é"), "plain é");
    }

    #[test]
    fn documents_are_well_formed() {
        let mut s = Svg::with_defs(10.0, 20.0, Some(11.0), "<pattern id=\"p\"/>\n");
        s.text(1.0, 2.0, "", "x<y");
        let t = s.finish();
        assert!(t.starts_with("<svg ") && t.ends_with("</svg>\n"), "{t}");
        assert!(
            t.contains(r#"width="10" height="20" viewBox="0 0 10.0 20.0""#) && t.contains(r#"font-size="11""#),
            "{t}"
        );
        let defs = t.find("<defs>").unwrap();
        assert!(defs < t.find("fill=\"white\"").unwrap());
        assert!(t.contains(r#"<text x="1.0" y="2.0">x&lt;y</text>"#), "{t}");
        let opt = resvg::usvg::Options::default();
        resvg::usvg::Tree::from_str(&t, &opt).unwrap();
    }
}
