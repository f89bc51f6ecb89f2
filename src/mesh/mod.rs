//! 2D polygon meshes: the domain `M` of the network formulation (docs/formulation.md §1).
//!
//! A [`Mesh`] is a planar polygon mesh (mostly quads, any n-gons allowed) with a half-edge
//! structure built once by [`Mesh::from_polygons`], which also validates the input (see
//! [`MeshError`]). The module is self-contained: it depends on nothing else in the crate.
//!
//! # Numbering
//!
//! - Vertex and face ids are the input indices.
//! - Edges are numbered in order of first appearance when walking the (CCW-normalised) face loops
//!   in face order: face 0's loop first, starting at its first vertex.
//! - Edge `e` has half-edges `2e` and `2e + 1`. Half-edge `2e` runs `a → b` where
//!   `(a, b) = edge_vertices(e)`, which is the direction the edge is walked by the first face that
//!   uses it; so half-edge `2e` always has a face on its left and only `2e + 1` can be a
//!   boundary (faceless) half-edge.
//! - [`Mesh::outgoing`] lists the half-edges leaving a vertex in counter-clockwise angular order.
//!   For an interior vertex the list starts at the smallest half-edge id and wraps around (the face
//!   between `outgoing[last]` and `outgoing[0]` is `he_face(outgoing[last])`). For a boundary
//!   vertex the list starts right after the boundary gap: `outgoing[0]` and `outgoing[last]` are
//!   the two boundary edges, `he_face(outgoing[i])` is the face between `outgoing[i]` and
//!   `outgoing[i + 1]`, and `he_face(outgoing[last])` is `None` (the gap).
//!
//! A mesh may have several connected components and holes, but every vertex must have a single
//! fan of faces: faces touching only at a corner are rejected
//! ([`MeshError::NonManifoldVertex`]). Accessors panic on ids out of range, like slice indexing.
//!
//! # Files
//!
//! - JSON (serde): `{ "vertices": [[x, y], …], "faces": [[i, j, k, l], …] }` (faces written
//!   counter-clockwise); deserialising validates through [`Mesh::from_polygons`] and rejects
//!   unknown fields. Coordinates round-trip bit-exactly only if serde_json's `float_roundtrip`
//!   feature is on (otherwise its float parser may be off by one ulp).
//! - Wavefront OBJ: [`to_obj`] / [`from_obj`].
//!
//! # Tools
//!
//! [`grid`], [`clipped_grid`] and [`jitter`] generate meshes; [`subdivide`](fn@subdivide) splits
//! every n-gon into n quads without moving the old vertices.

mod error;
pub mod generate;
mod halfedge;
mod ids;
pub mod obj;
pub(crate) mod paths;
mod serde_impl;
pub mod subdivide;
#[cfg(test)]
mod tests;

pub use self::error::{DegenerateReason, MeshError};
pub use self::generate::{clipped_grid, clipped_grid_on_lattice, grid, jitter, try_grid};
pub use self::halfedge::Mesh;
pub use self::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
pub use self::obj::{from_obj, to_obj, ObjError, ObjErrorKind};
pub use self::subdivide::{subdivide, Subdivision};
