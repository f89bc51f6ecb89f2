//! Boundary-aligned cross fields on a region (Yang, Wang, Vouga, Wonka 2013, §5): the streets of
//! a region follow streamlines of a cross field — at each point two orthogonal directions —
//! aligned with the region's boundary.
//!
//! The region is triangulated ([`crate::geometry::cdt`]) and the field stored per vertex in the
//! power representation `u = r·e^{4iθ}` (a cross is invariant under quarter turns, `u` is not
//! ambiguous), interpolated linearly inside triangles. Two constructions (the paper's supplement
//! gives no algorithms; these are the standard resolutions):
//!
//! - [`FieldMethod::Smooth`]: the smoothest field with the boundary's tangent as Dirichlet data,
//!   `min Σ w_ij |u_i − u_j|²` with cotangent weights (Knöppel, Crane, Pinkall, Schröder 2013;
//!   Ray, Vallet, Lévy 2008) — [`methods::smooth`];
//! - [`FieldMethod::Distance`]: the paper's "D-field", aligned with the gradient of the distance
//!   to the boundary (its level sets are offsets of the boundary), lightly smoothed to round the
//!   medial axis' kinks — [`methods::distance`].
//!
//! Singularities are found per triangle: the turning of `u` around a triangle is `2πk`, its
//! index `k/4` ([`singular`]). The queries a streamline tracer
//! needs ([`CrossField::locate`], [`CrossField::sample`], [`CrossField::direction`],
//! [`CrossField::divergence`]) go through a uniform grid of triangle buckets ([`grid`]).
//! [`output`] writes `field.json` and a picture.

pub mod grid;
pub mod methods;
pub mod output;
pub mod singular;
mod solve;
#[cfg(test)]
mod tests;

pub use output::{field_json, write_field, FieldJson};
pub use singular::Singularity;

use crate::geometry::cdt::{self, CdtError, Mesh};
use crate::geometry::{Polygon, P};
use grid::Grid;
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;
use thiserror::Error;

/// A complex number `[re, im]`.
pub type C = [f64; 2];

/// How the field is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FieldMethod {
    /// The smoothest boundary-aligned field (harmonic `u` with the boundary's `τ⁴`).
    Smooth,
    /// The distance field: aligned with the gradient of the distance to the boundary.
    Distance,
}

impl FieldMethod {
    /// The name used in files and on the command line (`smooth`, `distance`).
    pub fn name(self) -> &'static str {
        match self {
            FieldMethod::Smooth => "smooth",
            FieldMethod::Distance => "distance",
        }
    }
}

impl std::str::FromStr for FieldMethod {
    type Err = String;
    /// `smooth` or `distance` (any case).
    fn from_str(s: &str) -> Result<Self, String> {
        [FieldMethod::Smooth, FieldMethod::Distance]
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown field `{s}` (known: smooth, distance)"))
    }
}

/// What a field is built with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FieldOptions {
    /// The construction.
    pub method: FieldMethod,
    /// The triangulation's target edge length (metres).
    pub h: f64,
}

/// Why a field could not be built or written.
#[derive(Debug, Error)]
pub enum FieldError {
    /// The region could not be triangulated (or `h` was refused).
    #[error("triangulating the region: {0}")]
    Triangulation(#[from] CdtError),
    /// A file could not be written.
    #[error("writing {}: {source}", path.display())]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The picture could not be rasterised.
    #[error("field picture: {0}")]
    Render(#[from] crate::render::RenderError),
}

/// The field at a point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// The cross' angle `arg(u)/4` (radians, in `(−π/4, π/4]`); the cross is `θ + kπ/2`.
    pub theta: f64,
    /// `|u|`: 1 on the boundary, smaller where the field is smoothed over (near singularities).
    pub magnitude: f64,
    /// The triangle the point is in.
    pub triangle: usize,
}

/// A cross field on a triangulated region.
#[derive(Clone, Debug, Serialize)]
pub struct CrossField {
    method: FieldMethod,
    h: f64,
    boundary: Vec<Vec<P>>,
    vertices: Vec<P>,
    triangles: Vec<[usize; 3]>,
    on_boundary: Vec<bool>,
    power: Vec<C>,
    singularities: Vec<Singularity>,
    #[serde(skip)]
    grid: Grid,
}

impl CrossField {
    /// Triangulates `region` at `options.h` and builds the field by `options.method`.
    pub fn new(region: &Polygon, options: &FieldOptions) -> Result<CrossField, FieldError> {
        let mesh = cdt::triangulate(region, options.h)?;
        let power = match options.method {
            FieldMethod::Smooth => methods::smooth(&mesh),
            FieldMethod::Distance => methods::distance(&mesh, region, options.h),
        };
        let boundary = region.rings().map(<[P]>::to_vec).collect();
        Ok(CrossField::from_power(options.method, options.h, boundary, mesh, power))
    }

    /// A field from its per-vertex power values on a mesh (singularities and the grid computed).
    fn from_power(method: FieldMethod, h: f64, boundary: Vec<Vec<P>>, mesh: Mesh, power: Vec<C>) -> CrossField {
        let singularities = singular::singularities(&mesh.vertices, &mesh.triangles, &power);
        let grid = Grid::new(&mesh.vertices, &mesh.triangles);
        CrossField {
            method,
            h,
            boundary,
            vertices: mesh.vertices,
            triangles: mesh.triangles,
            on_boundary: mesh.on_boundary,
            power,
            singularities,
            grid,
        }
    }

    /// The construction used.
    pub fn method(&self) -> FieldMethod {
        self.method
    }

    /// The triangulation's target edge length (metres).
    pub fn h(&self) -> f64 {
        self.h
    }

    /// The region's rings (outer counter-clockwise, then the holes clockwise).
    pub fn boundary(&self) -> &[Vec<P>] {
        &self.boundary
    }

    /// The mesh vertices.
    pub fn vertices(&self) -> &[P] {
        &self.vertices
    }

    /// The mesh triangles (counter-clockwise).
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Whether each vertex is on the boundary.
    pub fn on_boundary(&self) -> &[bool] {
        &self.on_boundary
    }

    /// The vertices not on the boundary, in order.
    pub fn inner_vertices(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.vertices.len()).filter(|&v| !self.on_boundary[v])
    }

    /// The per-vertex power values `u = r·e^{4iθ}` as `[re, im]`.
    pub fn power(&self) -> &[C] {
        &self.power
    }

    /// The cross angle `arg(u)/4` at vertex `v` (radians).
    pub fn theta(&self, v: usize) -> f64 {
        arg(self.power[v]) / 4.0
    }

    /// The singularities (index ±1/4, …), in triangle order.
    pub fn singularities(&self) -> &[Singularity] {
        &self.singularities
    }

    /// The triangle containing `p`, or `None` outside the region.
    pub fn locate(&self, p: P) -> Option<usize> {
        self.grid.locate(&self.vertices, &self.triangles, p)
    }

    /// The field at `p` (barycentric interpolation of `u`), or `None` outside the region.
    pub fn sample(&self, p: P) -> Option<Sample> {
        let t = self.locate(p)?;
        let l = grid::barycentric(&self.vertices, self.triangles[t], p);
        let mut u = [0.0; 2];
        for (k, &v) in self.triangles[t].iter().enumerate() {
            u[0] += l[k] * self.power[v][0];
            u[1] += l[k] * self.power[v][1];
        }
        Some(Sample { theta: arg(u) / 4.0, magnitude: u[0].hypot(u[1]), triangle: t })
    }

    /// The unit vector among the cross' four directions at `p` nearest to `along` (largest dot
    /// product), or `None` outside the region.
    pub fn direction(&self, p: P, along: P) -> Option<P> {
        let s = self.sample(p)?;
        Some(branch(s.theta, along))
    }

    /// The divergence of the unit vector field in `triangle` whose vertex values are each
    /// vertex's cross direction nearest to `along`, interpolated linearly (a constant per
    /// triangle). Positive where streamlines along that direction spread apart. Panics if
    /// `triangle` is not a triangle index (take it from [`CrossField::locate`] or a [`Sample`]).
    pub fn divergence(&self, triangle: usize, along: P) -> f64 {
        let tri = self.triangles[triangle];
        let [a, b, c] = tri.map(|v| self.vertices[v]);
        let area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area2 == 0.0 {
            return 0.0;
        }
        // ∇λ_a = (b_y − c_y, c_x − b_x) / 2A, and cyclically.
        let grads = [[b[1] - c[1], c[0] - b[0]], [c[1] - a[1], a[0] - c[0]], [a[1] - b[1], b[0] - a[0]]];
        let mut div = 0.0;
        for (k, &v) in tri.iter().enumerate() {
            let d = branch(self.theta(v), along);
            div += d[0] * grads[k][0] + d[1] * grads[k][1];
        }
        div / area2
    }
}

/// The argument of a complex number, in `(−π, π]`.
pub fn arg(u: C) -> f64 {
    let a = u[1].atan2(u[0]);
    if a <= -std::f64::consts::PI {
        std::f64::consts::PI
    } else {
        a
    }
}

/// `τ⁴` for a unit vector `τ` read as a complex number.
pub fn pow4(t: P) -> C {
    let sq = [t[0] * t[0] - t[1] * t[1], 2.0 * t[0] * t[1]];
    [sq[0] * sq[0] - sq[1] * sq[1], 2.0 * sq[0] * sq[1]]
}

/// Of the unit vectors at angles `theta + kπ/2`, the one with the largest dot product with
/// `along` (the first, `k = 0`, when `along` is zero).
fn branch(theta: f64, along: P) -> P {
    let mut best = [theta.cos(), theta.sin()];
    let mut score = best[0] * along[0] + best[1] * along[1];
    for k in 1..4 {
        let a = theta + k as f64 * FRAC_PI_2;
        let d = [a.cos(), a.sin()];
        let s = d[0] * along[0] + d[1] * along[1];
        if s > score {
            (best, score) = (d, s);
        }
    }
    best
}
