//! Typed element ids.

use serde::{Deserialize, Serialize};
use std::fmt;

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
        pub struct $name(pub u32);

        impl $name {
            /// The id as an index into per-element arrays.
            #[inline]
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}", self.0)
            }
        }
    };
}

id_type!(
    /// A vertex of a [`Mesh`](super::Mesh): the index of its position in the input.
    VertexId
);
id_type!(
    /// An undirected edge of a [`Mesh`](super::Mesh); its half-edges are `2e` and `2e + 1`.
    EdgeId
);
id_type!(
    /// A face of a [`Mesh`](super::Mesh): the index of its loop in the input.
    FaceId
);
id_type!(
    /// A directed half-edge of a [`Mesh`](super::Mesh); half-edge `h` belongs to edge `h / 2`.
    HalfEdgeId
);
