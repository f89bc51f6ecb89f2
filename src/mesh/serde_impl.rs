//! JSON (serde) form of a [`Mesh`]: `{ "vertices": [[x, y], …], "faces": [[i, j, k, l], …] }`.

use super::halfedge::Mesh;
use super::ids::VertexId;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

#[derive(Serialize)]
struct MeshRef<'a> {
    vertices: &'a [[f64; 2]],
    faces: Vec<&'a [VertexId]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshData {
    vertices: Vec<[f64; 2]>,
    faces: Vec<Vec<u32>>,
}

impl Serialize for Mesh {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        MeshRef { vertices: self.positions(), faces: self.faces().map(|f| self.face_vertices(f)).collect() }
            .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Mesh {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let data = MeshData::deserialize(deserializer)?;
        Mesh::from_polygons(data.vertices, data.faces).map_err(serde::de::Error::custom)
    }
}
