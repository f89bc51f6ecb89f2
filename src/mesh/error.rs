//! Mesh validation errors.

use super::ids::{FaceId, VertexId};
use std::fmt;

/// Why [`Mesh::from_polygons`](super::Mesh::from_polygons) (or a generator) rejected its input.
///
/// Checks run in this order and the first failure is reported (within one check, the smallest
/// offending id): [`Empty`](Self::Empty) / [`TooLarge`](Self::TooLarge),
/// [`NonFinitePosition`](Self::NonFinitePosition), [`DuplicateVertex`](Self::DuplicateVertex),
/// [`BadIndex`](Self::BadIndex) and the combinatorial [`DegenerateFace`](Self::DegenerateFace)
/// reasons (per face, in face order), [`IsolatedVertex`](Self::IsolatedVertex), the geometric
/// [`DegenerateFace`](Self::DegenerateFace) reasons, [`NonManifoldEdge`](Self::NonManifoldEdge),
/// [`InconsistentOrientation`](Self::InconsistentOrientation),
/// [`NonManifoldVertex`](Self::NonManifoldVertex), [`OverlappingFaces`](Self::OverlappingFaces).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MeshError {
    /// The mesh has no faces (or a generator produced none).
    #[error("empty mesh: {reason}")]
    Empty {
        /// What was empty.
        reason: String,
    },
    /// More elements than 32-bit ids can number.
    #[error("mesh too large: {reason}")]
    TooLarge {
        /// What overflowed.
        reason: String,
    },
    /// A generator was called with unusable parameters (e.g. a non-positive spacing).
    #[error("invalid generator input: {reason}")]
    InvalidInput {
        /// What is wrong.
        reason: String,
    },
    /// A vertex position has a NaN or infinite coordinate.
    #[error("vertex {v} has a non-finite position")]
    NonFinitePosition {
        /// The vertex.
        v: VertexId,
    },
    /// Two vertices lie at the same position (within 1e-12); `a < b`.
    #[error("vertices {a} and {b} are at the same position")]
    DuplicateVertex {
        /// The smaller vertex id.
        a: VertexId,
        /// The larger vertex id.
        b: VertexId,
    },
    /// A face refers to a vertex index that does not exist.
    #[error("face {face} refers to vertex index {index}, which does not exist")]
    BadIndex {
        /// The face.
        face: FaceId,
        /// The bad vertex index.
        index: u32,
    },
    /// A face is degenerate (see [`DegenerateReason`]).
    #[error("face {face} is degenerate: {reason}")]
    DegenerateFace {
        /// The face.
        face: FaceId,
        /// Why.
        reason: DegenerateReason,
    },
    /// A vertex is used by no face.
    #[error("vertex {v} is isolated (used by no face)")]
    IsolatedVertex {
        /// The vertex.
        v: VertexId,
    },
    /// An edge is used by more than two faces; `a < b`.
    #[error("edge ({a}, {b}) is used by more than two faces")]
    NonManifoldEdge {
        /// The smaller endpoint.
        a: VertexId,
        /// The larger endpoint.
        b: VertexId,
    },
    /// The face winds the other way from the others (some faces clockwise, some counter-clockwise),
    /// or, after normalisation, uses an edge in the same direction as an earlier face (the two
    /// faces lie on the same side of that edge, i.e. they overlap).
    #[error("face {face} is inconsistently oriented with the rest of the mesh (or overlaps a neighbour)")]
    InconsistentOrientation {
        /// The face.
        face: FaceId,
    },
    /// The faces around a vertex do not form one disk (interior vertex) or one half-disk
    /// (boundary vertex), e.g. two faces touching only at this corner. Such meshes are
    /// rejected: one-rings, boundary and T-junction logic all assume a single fan per vertex
    /// (use [`clipped_grid`](super::clipped_grid), which removes diagonal-only contacts).
    #[error("vertex {v} is non-manifold (its faces do not form a single fan)")]
    NonManifoldVertex {
        /// The vertex.
        v: VertexId,
    },
    /// The corner angles of the faces around a vertex do not fit a planar fan: at an interior
    /// vertex they must add up to one turn (within 1e-6 rad), at a boundary vertex to less than
    /// one turn (by more than 1e-9 rad). Otherwise faces fold over each other.
    #[error("faces around vertex {v} overlap (corner angles do not add up to one turn)")]
    OverlappingFaces {
        /// The vertex.
        v: VertexId,
    },
}

/// Why a face is degenerate.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum DegenerateReason {
    /// Fewer than three vertices.
    TooFewVertices,
    /// The loop visits this vertex twice.
    RepeatedVertex(VertexId),
    /// Zero or near-zero area (|area| ≤ 1e-12 · perimeter²).
    ZeroArea,
    /// The loop crosses or touches itself.
    SelfIntersecting,
}

impl fmt::Display for DegenerateReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooFewVertices => write!(f, "fewer than 3 vertices"),
            Self::RepeatedVertex(v) => write!(f, "vertex {v} appears twice"),
            Self::ZeroArea => write!(f, "zero or near-zero area"),
            Self::SelfIntersecting => write!(f, "the boundary intersects itself"),
        }
    }
}
