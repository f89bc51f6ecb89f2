//! Wavefront OBJ reading and writing (2D: `z` is written as 0 and ignored on reading).
//!
//! Read: `v x y [z [w]]` (also `v x y z r g b` vertex colours; everything after `y` is ignored),
//! `f a b c …` with index forms `a`, `a/t`, `a//n`, `a/t/n` (only `a` is used; texture and normal
//! indices are not checked), 1-based indices, negative indices relative to the vertices read so
//! far (`-1` is the last one). Comments (`#` to end of line) and blank lines are skipped, and so
//! are the statements `o`, `g`, `s`, `mg`, `usemtl`, `mtllib`, `vt`, `vn`, `vp`, `l`, `p`. Any
//! other statement is an error. The result is validated by [`Mesh::from_polygons`], so every
//! vertex must be used by a face.

use super::error::MeshError;
use super::halfedge::Mesh;
use std::fmt::{self, Write as _};

/// An error reading an OBJ file: a 1-based line number and what went wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjError {
    /// 1-based line of the offending statement; 0 if the error concerns the whole file
    /// (e.g. it has no faces).
    pub line: usize,
    /// What went wrong.
    pub kind: ObjErrorKind,
}

/// What went wrong reading an OBJ file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ObjErrorKind {
    /// A statement keyword this reader does not know.
    UnknownStatement(String),
    /// A token that should be a number is not one.
    NotANumber(String),
    /// A coordinate is NaN or infinite.
    NonFiniteNumber(String),
    /// A `v` statement with fewer than two coordinates.
    TooFewCoordinates(usize),
    /// A `v` statement with more than six numbers.
    TooManyCoordinates(usize),
    /// An `f` statement with fewer than three vertices.
    TooFewFaceVertices(usize),
    /// A face vertex token that is not an integer index (`a`, `a/t`, `a//n`, `a/t/n`).
    BadIndex(String),
    /// Index 0 (OBJ indices are 1-based).
    ZeroIndex,
    /// A face refers to a vertex that does not exist (`vertices` is how many exist: so far for a
    /// negative index, in the whole file for a positive one).
    MissingVertex {
        /// The index as written.
        index: i64,
        /// Number of vertices it could refer to.
        vertices: usize,
    },
    /// The polygons do not form a valid mesh. Ids in the inner error are 0-based (vertex `k` is
    /// the `k + 1`-th `v` statement, face `k` the `k + 1`-th `f` statement).
    Mesh(MeshError),
}

impl fmt::Display for ObjErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnknownStatement(s) => write!(f, "unknown statement `{s}`"),
            Self::NotANumber(s) => write!(f, "`{s}` is not a number"),
            Self::NonFiniteNumber(s) => write!(f, "`{s}` is not a finite number"),
            Self::TooFewCoordinates(n) => {
                write!(f, "vertex has {n} coordinate(s), need at least x and y")
            }
            Self::TooManyCoordinates(n) => {
                write!(f, "vertex has {n} numbers, at most 6 are allowed")
            }
            Self::TooFewFaceVertices(n) => write!(f, "face has {n} vertex(es), need at least 3"),
            Self::BadIndex(s) => write!(f, "`{s}` is not a vertex index"),
            Self::ZeroIndex => write!(f, "vertex index 0 (OBJ indices start at 1)"),
            Self::MissingVertex { index, vertices } => {
                write!(f, "vertex index {index} refers to a missing vertex ({vertices} available)")
            }
            Self::Mesh(e) => write!(f, "invalid mesh (0-based ids): {e}"),
        }
    }
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line > 0 {
            write!(f, "OBJ line {}: {}", self.line, self.kind)
        } else {
            write!(f, "OBJ: {}", self.kind)
        }
    }
}

impl std::error::Error for ObjError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            ObjErrorKind::Mesh(e) => Some(e),
            _ => None,
        }
    }
}

/// Writes a mesh as OBJ: a comment header, `v x y 0` per vertex (shortest round-trip decimal
/// form) and `f …` per face (1-based, counter-clockwise). [`from_obj`] reads it back to an equal
/// mesh.
pub fn to_obj(mesh: &Mesh) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# netspec mesh: {} vertices, {} edges, {} faces",
        mesh.num_vertices(),
        mesh.num_edges(),
        mesh.num_faces()
    );
    for p in mesh.positions() {
        let _ = writeln!(s, "v {:?} {:?} 0", p[0], p[1]);
    }
    for f in mesh.faces() {
        s.push('f');
        for v in mesh.face_vertices(f) {
            let _ = write!(s, " {}", v.0 as u64 + 1);
        }
        s.push('\n');
    }
    s
}

/// Shortens a token for an error message.
fn token(s: &str) -> String {
    const MAX: usize = 40;
    if s.chars().count() <= MAX {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(MAX).collect();
        t.push('…');
        t
    }
}

/// Reads a mesh from OBJ text (see the [module docs](self)). Never panics.
pub fn from_obj(text: &str) -> Result<Mesh, ObjError> {
    let mut positions: Vec<[f64; 2]> = Vec::new();
    let mut vertex_lines: Vec<usize> = Vec::new();
    // Faces with raw resolved indices (0-based, possibly ≥ number of vertices for forward refs).
    let mut raw_faces: Vec<Vec<i64>> = Vec::new();
    let mut face_lines: Vec<usize> = Vec::new();

    for (k, raw_line) in text.lines().enumerate() {
        let line = k + 1;
        let err = |kind| Err(ObjError { line, kind });
        let content = raw_line.split('#').next().unwrap_or("");
        let mut tokens = content.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        match keyword {
            "v" => {
                let mut xy = [0.0; 2];
                let mut n = 0usize;
                for t in tokens {
                    let x: f64 = match t.parse() {
                        Ok(x) => x,
                        Err(_) => return err(ObjErrorKind::NotANumber(token(t))),
                    };
                    if !x.is_finite() {
                        return err(ObjErrorKind::NonFiniteNumber(token(t)));
                    }
                    if n < 2 {
                        xy[n] = x;
                    }
                    n += 1;
                }
                if n < 2 {
                    return err(ObjErrorKind::TooFewCoordinates(n));
                }
                if n > 6 {
                    return err(ObjErrorKind::TooManyCoordinates(n));
                }
                positions.push(xy);
                vertex_lines.push(line);
            }
            "f" => {
                let mut face = Vec::new();
                for t in tokens {
                    let first = t.split('/').next().unwrap_or("");
                    let rest_ok = t.split('/').skip(1).all(|s| s.is_empty() || s.parse::<i64>().is_ok());
                    let idx: i64 = match first.parse() {
                        Ok(i) if rest_ok && t.split('/').count() <= 3 => i,
                        _ => return err(ObjErrorKind::BadIndex(token(t))),
                    };
                    let resolved = if idx > 0 {
                        idx - 1
                    } else if idx < 0 {
                        let r = positions.len() as i64 + idx;
                        if r < 0 {
                            return err(ObjErrorKind::MissingVertex { index: idx, vertices: positions.len() });
                        }
                        r
                    } else {
                        return err(ObjErrorKind::ZeroIndex);
                    };
                    face.push(resolved);
                }
                if face.len() < 3 {
                    return err(ObjErrorKind::TooFewFaceVertices(face.len()));
                }
                raw_faces.push(face);
                face_lines.push(line);
            }
            "o" | "g" | "s" | "mg" | "usemtl" | "mtllib" | "vt" | "vn" | "vp" | "l" | "p" => {}
            other => return err(ObjErrorKind::UnknownStatement(token(other))),
        }
    }

    // Resolve forward (positive) references now that all vertices are known.
    let nv = positions.len();
    let mut faces = Vec::with_capacity(raw_faces.len());
    for (face, &line) in raw_faces.iter().zip(&face_lines) {
        let mut lp = Vec::with_capacity(face.len());
        for &i in face {
            match u32::try_from(i) {
                Ok(u) if (u as usize) < nv => lp.push(u),
                _ => return Err(ObjError { line, kind: ObjErrorKind::MissingVertex { index: i + 1, vertices: nv } }),
            }
        }
        faces.push(lp);
    }

    Mesh::from_polygons(positions, faces.clone()).map_err(|e| {
        let line = mesh_error_line(&e, &vertex_lines, &face_lines, &faces);
        ObjError { line, kind: ObjErrorKind::Mesh(e) }
    })
}

/// The line of the statement a mesh error is about (0 if none).
fn mesh_error_line(e: &MeshError, vertex_lines: &[usize], face_lines: &[usize], faces: &[Vec<u32>]) -> usize {
    let vline = |v: super::VertexId| vertex_lines.get(v.index()).copied().unwrap_or(0);
    let fline = |f: super::FaceId| face_lines.get(f.index()).copied().unwrap_or(0);
    match e {
        MeshError::NonFinitePosition { v }
        | MeshError::IsolatedVertex { v }
        | MeshError::NonManifoldVertex { v }
        | MeshError::OverlappingFaces { v } => vline(*v),
        MeshError::DuplicateVertex { b, .. } => vline(*b),
        MeshError::BadIndex { face, .. }
        | MeshError::DegenerateFace { face, .. }
        | MeshError::InconsistentOrientation { face } => fline(*face),
        MeshError::NonManifoldEdge { a, b } => {
            // The third face that uses the edge.
            let mut count = 0;
            for (f, lp) in faces.iter().enumerate() {
                let n = lp.len();
                if (0..n).any(|k| {
                    let (x, y) = (lp[k], lp[(k + 1) % n]);
                    (x.min(y), x.max(y)) == (a.0, b.0)
                }) {
                    count += 1;
                    if count == 3 {
                        return face_lines.get(f).copied().unwrap_or(0);
                    }
                }
            }
            0
        }
        MeshError::Empty { .. } | MeshError::TooLarge { .. } | MeshError::InvalidInput { .. } => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{grid, jitter, FaceId, VertexId};
    use proptest::prelude::*;

    const MIXED: &str = include_str!("../../fixtures/mesh/mixed.obj");

    #[test]
    fn obj_round_trip() {
        let m = jitter(&grid(5, 4, 0.7), 0.3, 9);
        let text = to_obj(&m);
        let back = from_obj(&text).unwrap();
        assert_eq!(back, m);
        assert_eq!(to_obj(&back), text);
    }

    #[test]
    fn obj_fixture_forms() {
        // Comments, o/g/s/usemtl, slash forms, negative indices, z and vertex colours.
        let m = from_obj(MIXED).unwrap();
        assert_eq!((m.num_vertices(), m.num_faces()), (8, 3));
        assert_eq!(m.face_size(FaceId(0)), 4);
        assert_eq!(m.face_size(FaceId(1)), 3);
        assert_eq!(m.face_size(FaceId(2)), 5);
        assert_eq!(from_obj(&to_obj(&m)).unwrap(), m);
    }

    #[test]
    fn obj_clockwise_input_is_normalised() {
        let m = from_obj("v 0 0\nv 0 1\nv 1 1\nv 1 0\nf 1 2 3 4\n").unwrap();
        assert_eq!(m.face_vertices(FaceId(0)), &[VertexId(0), VertexId(3), VertexId(2), VertexId(1)]);
    }

    fn err(text: &str) -> ObjError {
        from_obj(text).unwrap_err()
    }

    #[test]
    fn obj_errors_name_the_line() {
        let e = err("v 0 0\nv 1 0\nv 1 1\nf 1 2 4\n");
        assert_eq!(e.line, 4);
        assert_eq!(e.kind, ObjErrorKind::MissingVertex { index: 4, vertices: 3 });
        assert!(e.to_string().starts_with("OBJ line 4:"), "{e}");

        let e = err("v 0 0\nv 1 0\nf -1 -2 -3\n");
        assert_eq!((e.line, e.kind), (3, ObjErrorKind::MissingVertex { index: -3, vertices: 2 }));

        let e = err("# header\nv 0 zero\n");
        assert_eq!((e.line, e.kind), (2, ObjErrorKind::NotANumber("zero".into())));

        let e = err("v 0 0\nv 1 0\nv 1 1\nf 1 2 x\n");
        assert_eq!((e.line, e.kind), (4, ObjErrorKind::BadIndex("x".into())));

        let e = err("v 0 0\nv 1 0\nv 1 1\nf 1 2 0\n");
        assert_eq!((e.line, e.kind), (4, ObjErrorKind::ZeroIndex));

        let e = err("v 0 0\nv 1 0\nv 1 1\nf 1 2\n");
        assert_eq!((e.line, e.kind), (4, ObjErrorKind::TooFewFaceVertices(2)));

        let e = err("v 0 0\nv 1 0\nv 1 1\nv 5 5\nf 1 2 3\n");
        assert_eq!((e.line, e.kind), (4, ObjErrorKind::Mesh(MeshError::IsolatedVertex { v: VertexId(3) })));

        let e = err("v 0\n");
        assert_eq!((e.line, e.kind), (1, ObjErrorKind::TooFewCoordinates(1)));

        let e = err("v 0 inf\n");
        assert_eq!((e.line, e.kind), (1, ObjErrorKind::NonFiniteNumber("inf".into())));

        let e = err("vx 0 0\n");
        assert_eq!((e.line, e.kind), (1, ObjErrorKind::UnknownStatement("vx".into())));

        let e = err("# nothing\n");
        assert_eq!(e.line, 0);
        assert!(matches!(e.kind, ObjErrorKind::Mesh(MeshError::Empty { .. })));

        // Third face on edge (1, 2) (0-based 0–1) is on line 8.
        let e = err("v 0 0\nv 1 0\nv 0.5 1\nv 0.5 -1\nv 0.5 2\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
        assert_eq!(e.line, 8);
        assert_eq!(e.kind, ObjErrorKind::Mesh(MeshError::NonManifoldEdge { a: VertexId(0), b: VertexId(1) }));
        assert!(e.to_string().contains("edge (0, 1)"), "{e}");

        let e = err("v 0 0\nv 1 0\nv 0 1\nf 1 2 3/1/1/1\n");
        assert_eq!(e.kind, ObjErrorKind::BadIndex("3/1/1/1".into()));
    }

    fn line_strategy() -> impl Strategy<Value = String> {
        let num = prop_oneof![
            (-5i32..5).prop_map(|i| i.to_string()),
            any::<f64>().prop_map(|x| format!("{x:?}")),
            "[-0-9.eE+a-z]{0,6}",
        ];
        let idx = prop_oneof![
            (-12i64..12).prop_map(|i| i.to_string()),
            any::<i64>().prop_map(|i| i.to_string()),
            ((-12i64..12), (0i64..3)).prop_map(|(i, t)| format!("{i}/{t}/{t}")),
            (1i64..12).prop_map(|i| format!("{i}//1")),
            "[-0-9/]{0,5}",
        ];
        prop_oneof![
            3 => prop::collection::vec(num, 0..5).prop_map(|v| format!("v {}", v.join(" "))),
            3 => prop::collection::vec(idx, 0..7).prop_map(|v| format!("f {}", v.join(" "))),
            1 => "[ -~]{0,20}",
            1 => "\\PC{0,12}",
            1 => Just("# comment".to_string()),
            1 => Just("o thing".to_string()),
        ]
    }

    proptest! {
        #[test]
        fn from_obj_never_panics(lines in prop::collection::vec(line_strategy(), 0..25)) {
            let text = lines.join("\n");
            if let Ok(m) = from_obj(&text) {
                prop_assert_eq!(from_obj(&to_obj(&m)).unwrap(), m);
            }
        }

        #[test]
        fn from_obj_grid_lattice_never_panics(
            faces in prop::collection::vec(prop::collection::vec(1u32..10, 3..6), 1..6)
        ) {
            // Valid vertices, random faces: exercises the mesh validation paths.
            let mut text = String::new();
            for j in 0..3 { for i in 0..3 { text.push_str(&format!("v {i} {j}\n")); } }
            for f in &faces {
                text.push('f');
                for i in f { text.push_str(&format!(" {i}")); }
                text.push('\n');
            }
            let _ = from_obj(&text);
        }
    }
}
