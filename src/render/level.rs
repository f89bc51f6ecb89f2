//! A game level's layout: the blocks (one colour per block shape), the doors, and the
//! connectivity graph drawn over them (block centres joined through the doors), and the
//! obstacles, dark grey.

use super::writer::{Fit, Svg};
use std::fmt::Write;

/// A placed block.
pub struct LevelBlock {
    /// The placed polygon.
    pub polygon: Vec<[f64; 2]>,
    /// The node's name (written at the centre; nothing when empty).
    pub label: String,
    /// Index of the block shape (its colour).
    pub shape: usize,
    /// Where the graph node is drawn.
    pub centre: [f64; 2],
}

/// A level picture's contents, in level coordinates (y up).
pub struct LevelScene {
    /// The blocks.
    pub blocks: Vec<LevelBlock>,
    /// Doors: each a door-wide piece of a shared wall, with the indices of its two blocks.
    pub doors: Vec<([[f64; 2]; 2], usize, usize)>,
    /// Obstacles (fixed polygons no block may overlap), drawn dark grey.
    pub obstacles: Vec<Vec<[f64; 2]>>,
    /// A caption under the picture.
    pub caption: String,
}

const PALETTE: [&str; 8] = ["#c6dbef", "#fdd0a2", "#c7e9c0", "#dadaeb", "#fcbba1", "#d9d9d9", "#f2e2a0", "#b3e2cd"];

/// The picture as SVG text (about 640 pixels across).
pub fn level_svg(scene: &LevelScene) -> String {
    let pts = scene.blocks.iter().flat_map(|b| b.polygon.iter()).chain(scene.obstacles.iter().flatten());
    let fit = Fit::new(pts, 600.0);
    let (margin, w, h) = (fit.margin, fit.width, fit.height);
    let tx = |p: [f64; 2]| fit.tx(p);
    let mut svg = Svg::new(w, h, Some(12.0));
    for o in &scene.obstacles {
        let d: Vec<String> = o.iter().map(|&p| tx(p)).map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
        let _ = writeln!(
            svg,
            r##"<polygon class="obstacle" points="{}" fill="#737373" stroke="#333" stroke-width="1"/>"##,
            d.join(" ")
        );
    }
    for b in &scene.blocks {
        let d: Vec<String> = b.polygon.iter().map(|&p| tx(p)).map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
        let fill = PALETTE[b.shape % PALETTE.len()];
        let _ =
            writeln!(svg, r##"<polygon points="{}" fill="{fill}" stroke="#333" stroke-width="1.5"/>"##, d.join(" "));
    }
    for (door, _, _) in &scene.doors {
        let ((ax, ay), (bx, by)) = (tx(door[0]), tx(door[1]));
        let _ = writeln!(
            svg,
            r##"<line x1="{ax:.2}" y1="{ay:.2}" x2="{bx:.2}" y2="{by:.2}" stroke="#ffffff" stroke-width="4"/>"##
        );
    }
    for (door, i, j) in &scene.doors {
        let mid = [(door[0][0] + door[1][0]) / 2.0, (door[0][1] + door[1][1]) / 2.0];
        let pts = [tx(scene.blocks[*i].centre), tx(mid), tx(scene.blocks[*j].centre)];
        let d: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
        let _ =
            writeln!(svg, r##"<polyline points="{}" fill="none" stroke="#b2182b" stroke-width="1.5"/>"##, d.join(" "));
    }
    for b in &scene.blocks {
        let (x, y) = tx(b.centre);
        let _ = writeln!(svg, r##"<circle cx="{x:.2}" cy="{y:.2}" r="3.5" fill="#b2182b"/>"##);
        if !b.label.is_empty() {
            svg.text(x + 5.0, y - 5.0, "", &b.label);
        }
    }
    svg.text(margin, h - 8.0, "", &scene.caption);
    svg.finish()
}
