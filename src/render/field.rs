//! A cross field: the region's boundary, short crosses at a subsample of points, singularities
//! as dots (`+1/4` red, `−1/4` blue, larger for larger indices), and optional polylines
//! (streamlines) over them. Plain data in metres (y up).

use super::writer::{Fit, Svg};
use std::fmt::Write;

/// What a field picture shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FieldScene {
    /// The region's rings (outer ring and holes), each implicitly closed.
    pub rings: Vec<Vec<[f64; 2]>>,
    /// Crosses: where, and the angle of one arm (radians; the others at quarter turns).
    pub crosses: Vec<([f64; 2], f64)>,
    /// Half the length of a cross' arms (metres).
    pub arm: f64,
    /// Singularities: where, and the index.
    pub singularities: Vec<([f64; 2], f64)>,
    /// Polylines drawn over the crosses (streamlines).
    pub lines: Vec<Vec<[f64; 2]>>,
    /// A caption under the picture.
    pub caption: String,
}

/// The picture as SVG text (about 640 pixels across).
pub fn field_svg(scene: &FieldScene) -> String {
    let fit = Fit::new(scene.rings.iter().flatten(), 600.0);
    let (margin, scale, w, h) = (fit.margin, fit.scale, fit.width, fit.height);
    let tx = |p: [f64; 2]| fit.tx(p);
    let mut svg = Svg::new(w, h, Some(12.0));
    let path: String = scene
        .rings
        .iter()
        .filter(|r| !r.is_empty())
        .map(|r| {
            let pts: Vec<String> = r.iter().map(|&p| tx(p)).map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
            format!("M{}Z", pts.join(" L"))
        })
        .collect();
    let _ = writeln!(
        svg,
        r##"<path class="region" d="{path}" fill="#f7f7f7" fill-rule="evenodd" stroke="#252525" stroke-width="1.5"/>"##
    );
    let arm = scene.arm * scale;
    let mut d = String::new();
    for &(p, theta) in &scene.crosses {
        let (x, y) = tx(p);
        // y is flipped on the page: the arm at angle θ goes to (cos θ, −sin θ).
        let (c, s) = (theta.cos() * arm, -theta.sin() * arm);
        let _ = write!(d, "M{:.2},{:.2}L{:.2},{:.2}", x - c, y - s, x + c, y + s);
        let _ = write!(d, "M{:.2},{:.2}L{:.2},{:.2}", x + s, y - c, x - s, y + c);
    }
    let _ = writeln!(svg, r##"<path class="crosses" d="{d}" fill="none" stroke="#6baed6" stroke-width="1"/>"##);
    for line in scene.lines.iter().filter(|l| l.len() > 1) {
        let pts: Vec<String> = line.iter().map(|&p| tx(p)).map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
        let _ = writeln!(
            svg,
            r##"<polyline class="streamline" points="{}" fill="none" stroke="#d94801" stroke-width="1.5"/>"##,
            pts.join(" ")
        );
    }
    for &(p, index) in &scene.singularities {
        let (x, y) = tx(p);
        let fill = if index > 0.0 { "#d7301f" } else { "#2171b5" };
        let r = 3.0 + 2.0 * (index.abs() * 4.0 - 1.0).max(0.0);
        let _ = writeln!(
            svg,
            r##"<circle class="singularity" cx="{x:.2}" cy="{y:.2}" r="{r:.1}" fill="{fill}" stroke="#000" stroke-width="0.5"/>"##
        );
    }
    svg.text(margin, h - 8.0, "", &scene.caption);
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_rings_crosses_dots_and_lines() {
        let scene = FieldScene {
            rings: vec![vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]],
            crosses: vec![([5.0, 5.0], 0.0)],
            arm: 1.0,
            singularities: vec![([2.0, 2.0], 0.25), ([8.0, 8.0], -0.25)],
            lines: vec![vec![[1.0, 1.0], [9.0, 9.0]]],
            caption: "a <field>".into(),
        };
        let svg = field_svg(&scene);
        assert!(svg.contains(r##"fill="#d7301f""##) && svg.contains(r##"fill="#2171b5""##), "{svg}");
        assert!(svg.contains("class=\"streamline\"") && svg.contains("a &lt;field&gt;"), "{svg}");
        // The cross at the centre: arms of 2 × 60 px (60 px/m).
        assert!(svg.contains("M260.00,320.00L380.00,320.00M320.00,260.00L320.00,380.00"), "{svg}");
        resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
    }
}
