//! What `netspec field` writes: `field.json` (the mesh, the per-vertex cross angle and the
//! singularities, numbers rounded to 1e-6 so the same input gives the same bytes) and the
//! picture (`field.svg`, `field.png`).

use super::{CrossField, FieldError};
use crate::geometry::P;
use crate::render::field::{field_svg, FieldScene};
use serde::Serialize;
use std::path::Path;

/// `field.json`: `{"method", "vertices", "singularities": [{"x", "y", "index"}], "field":
/// {"points", "triangles", "theta"}}`, keys in that order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FieldJson {
    /// `smooth` or `distance`.
    pub method: String,
    /// The vertex count.
    pub vertices: usize,
    /// The singularities.
    pub singularities: Vec<SingularityJson>,
    /// The mesh and the angles.
    pub field: MeshJson,
}

/// A singularity in `field.json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SingularityJson {
    /// Where (the triangle's barycentre).
    pub x: f64,
    /// Where.
    pub y: f64,
    /// `±1/4`, …
    pub index: f64,
}

/// The mesh and the per-vertex cross angle in `field.json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshJson {
    /// Vertex positions.
    pub points: Vec<P>,
    /// Triangles (counter-clockwise vertex indices).
    pub triangles: Vec<[usize; 3]>,
    /// The cross angle per vertex (radians, `arg(u)/4`).
    pub theta: Vec<f64>,
}

/// Rounds to 1e-6 (and −0 to 0), so output bytes do not depend on the last bits.
fn round6(x: f64) -> f64 {
    let r = (x * 1e6).round() / 1e6;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// The contents of `field.json`.
pub fn field_json(field: &CrossField) -> FieldJson {
    FieldJson {
        method: field.method().name().into(),
        vertices: field.vertices().len(),
        singularities: field
            .singularities()
            .iter()
            .map(|s| SingularityJson { x: round6(s.at[0]), y: round6(s.at[1]), index: s.index })
            .collect(),
        field: MeshJson {
            points: field.vertices().iter().map(|p| p.map(round6)).collect(),
            triangles: field.triangles().to_vec(),
            theta: (0..field.vertices().len()).map(|v| round6(field.theta(v))).collect(),
        },
    }
}

/// The picture's contents: crosses at the inner vertex nearest each cell centre of a grid
/// about 30 cells across (no finer than 1.5 h), singularities, and `streamlines`.
pub fn field_scene(field: &CrossField, streamlines: &[Vec<P>]) -> FieldScene {
    let [lo, hi] = crate::geometry::polygon::bounds(field.vertices());
    let spacing = ((hi[0] - lo[0]).max(hi[1] - lo[1]) / 30.0).max(1.5 * field.h());
    let mut best: std::collections::BTreeMap<(i64, i64), (f64, usize)> = std::collections::BTreeMap::new();
    for v in field.inner_vertices() {
        let p = field.vertices()[v];
        let (fx, fy) = ((p[0] - lo[0]) / spacing, (p[1] - lo[1]) / spacing);
        let off = (fx - fx.floor() - 0.5).hypot(fy - fy.floor() - 0.5);
        let slot = best.entry((fx.floor() as i64, fy.floor() as i64)).or_insert((f64::INFINITY, v));
        if off < slot.0 {
            *slot = (off, v);
        }
    }
    let mut picked: Vec<usize> = best.values().map(|&(_, v)| v).collect();
    picked.sort_unstable();
    let crosses = picked.into_iter().map(|v| (field.vertices()[v], field.theta(v))).collect();
    let counts = |sign: f64| field.singularities().iter().filter(|s| s.index * sign > 0.0).count();
    FieldScene {
        rings: field.boundary().to_vec(),
        crosses,
        arm: 0.35 * spacing,
        singularities: field.singularities().iter().map(|s| (s.at, s.index)).collect(),
        lines: streamlines.to_vec(),
        caption: format!(
            "{} field, h = {} m, {} vertices; singularities: {} positive (red), {} negative (blue)",
            field.method().name(),
            field.h(),
            field.vertices().len(),
            counts(1.0),
            counts(-1.0)
        ),
    }
}

/// Writes `field.json`, `field.svg` and `field.png` into `dir` (created if missing), with
/// `streamlines` drawn over the field.
pub fn write_field(dir: &Path, field: &CrossField, streamlines: &[Vec<P>]) -> Result<(), FieldError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| FieldError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, bytes).map_err(io(&path))
    };
    let json = serde_json::to_string(&field_json(field)).expect("field JSON serialises") + "\n";
    write("field.json", json.as_bytes())?;
    let svg = field_svg(&field_scene(field, streamlines));
    write("field.svg", svg.as_bytes())?;
    write("field.png", &crate::render::png(&svg)?)
}
