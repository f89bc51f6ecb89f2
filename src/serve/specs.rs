//! Specs for the page: the embedded examples, specs under the root, paths kept under the root,
//! checking an edited spec (the command line's spec code), and the spec's picture.

use super::error::ApiError;
use crate::design::picture::mesh_scene;
use crate::render::network::{picture_points, svg};
use crate::render::Caption;
use crate::spec::{Problem, Spec, SpecErrorKind};
use serde::Serialize;
use std::path::{Component, Path, PathBuf};

/// The paper's examples (`models/`), embedded: name and TOML text.
pub const EXAMPLES: &[(&str, &str)] = &[
    ("fig1d", include_str!("../../models/fig1d.toml")),
    ("fig1e", include_str!("../../models/fig1e.toml")),
    ("fig2a", include_str!("../../models/fig2a.toml")),
    ("fig2b", include_str!("../../models/fig2b.toml")),
    ("fig2c", include_str!("../../models/fig2c.toml")),
    ("fig2d", include_str!("../../models/fig2d.toml")),
    ("fig2e", include_str!("../../models/fig2e.toml")),
    ("fig2f", include_str!("../../models/fig2f.toml")),
    ("fig2g", include_str!("../../models/fig2g.toml")),
    ("fig9b1", include_str!("../../models/fig9b1.toml")),
    ("fig9b2", include_str!("../../models/fig9b2.toml")),
    ("fig9b3", include_str!("../../models/fig9b3.toml")),
    ("fig9b4", include_str!("../../models/fig9b4.toml")),
    ("fig11a", include_str!("../../models/fig11a.toml")),
    ("fig11b", include_str!("../../models/fig11b.toml")),
];

/// The folder of runs under the root (never listed as specs).
pub const RUNS: &str = "runs";

/// One entry of the spec list.
#[derive(Serialize)]
pub struct Listed {
    /// `example` or `root`.
    pub source: &'static str,
    /// The example's name or the path under the root.
    pub id: String,
    /// The spec's name.
    pub name: String,
    /// Its description.
    pub description: String,
}

/// The embedded example `name`'s TOML text.
pub fn example(name: &str) -> Result<&'static str, ApiError> {
    EXAMPLES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| ApiError::not_found("example", format!("no example named `{name}`")))
}

/// Every example, then every `.toml` spec under the root (four folders deep, runs left out),
/// in path order.
pub fn list(root: &Path) -> Vec<Listed> {
    let mut out: Vec<Listed> = EXAMPLES
        .iter()
        .filter_map(|(n, t)| Spec::from_toml(t).ok().map(|s| (n, s)))
        .map(|(n, s)| Listed { source: "example", id: n.to_string(), name: s.name, description: s.description })
        .collect();
    let mut found = Vec::new();
    walk(root, root, 0, &mut found);
    found.sort();
    for rel in found {
        let text = std::fs::read_to_string(root.join(&rel)).unwrap_or_default();
        if let Ok(s) = Spec::from_toml(&text) {
            out.push(Listed { source: "root", id: rel, name: s.name, description: s.description });
        }
    }
    out
}

/// The pictures of `netspec city`, `traffic`, `layout` and `field` outputs that the page shows,
/// by file name, with their kind.
pub const OUTPUT_PICTURES: &[(&str, &str)] = &[
    ("city.svg", "city"),
    ("volume.svg", "traffic"),
    ("traveltime.svg", "traffic"),
    ("comparison.svg", "traffic"),
    ("layout.svg", "layout"),
    ("field.svg", "field"),
];

/// The kind of a `netspec grow` output's pictures.
pub const GROW: &str = "grow";

/// The pictures the page shows, in words (for errors).
pub fn shown() -> String {
    let names: Vec<&str> = OUTPUT_PICTURES.iter().map(|(n, _)| *n).collect();
    format!("{}, and a netspec grow output's network.svg and step-NNN.svg", names.join(", "))
}

/// One city, traffic, layout, field or grow picture under the root.
#[derive(Serialize)]
pub struct Output {
    /// `city`, `traffic`, `layout`, `field` or `grow`.
    pub kind: &'static str,
    /// The picture's path under the root.
    pub path: String,
}

/// Whether `name` is a grow snapshot's: `step-` digits `.svg`.
fn is_step_svg(name: &str) -> bool {
    name.strip_prefix("step-")
        .and_then(|r| r.strip_suffix(".svg"))
        .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
}

/// A file name that may be a picture the page shows (grow's only beside a grow output's files).
fn may_show(name: &str) -> bool {
    OUTPUT_PICTURES.iter().any(|(n, _)| *n == name) || name == "network.svg" || is_step_svg(name)
}

/// The kind of the picture at `path` if the page shows it: a city, traffic, layout or field
/// picture by its name, or `grow` for `network.svg` and `step-NNN.svg` beside a grow output's
/// `series.csv` and `network.json` (`netspec solve` writes a `network.svg` too, without them).
pub fn picture_kind(path: &Path) -> Option<&'static str> {
    let name = path.file_name()?.to_string_lossy();
    if let Some((_, kind)) = OUTPUT_PICTURES.iter().find(|(n, _)| *n == name) {
        return Some(kind);
    }
    let dir = path.parent()?;
    let grown = dir.join("series.csv").is_file() && dir.join("network.json").is_file();
    (grown && (name == "network.svg" || is_step_svg(&name))).then_some(GROW)
}

/// Every city, traffic, layout, field and grow picture under the root (four folders deep, runs
/// left out), in path order.
pub fn outputs(root: &Path) -> Vec<Output> {
    let mut found = Vec::new();
    walk_files(root, root, 0, &may_show, &mut found);
    found.sort();
    found.into_iter().filter_map(|path| Some(Output { kind: picture_kind(&root.join(&path))?, path })).collect()
}

fn walk(root: &Path, dir: &Path, depth: usize, found: &mut Vec<String>) {
    walk_files(root, dir, depth, &|name| name.ends_with(".toml"), found)
}

fn walk_files(root: &Path, dir: &Path, depth: usize, keep: &dyn Fn(&str) -> bool, found: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let (path, Ok(kind)) = (e.path(), e.file_type()) else { continue };
        // Symbolic links are not followed: the list never leads outside the root.
        if kind.is_dir() && depth < 4 && !(depth == 0 && e.file_name() == RUNS) {
            walk_files(root, &path, depth + 1, keep, found);
        } else if kind.is_file() && keep(&e.file_name().to_string_lossy()) {
            if let Ok(rel) = path.strip_prefix(root) {
                found.push(rel.to_string_lossy().into_owned());
            }
        }
    }
}

/// `rel` as a path under `root`: relative, no `.`/`..`, and (as far as it exists) not leading
/// outside the root through a symbolic link. `field` names the request's field in errors.
pub fn under_root(root: &Path, rel: &str, field: &str) -> Result<PathBuf, ApiError> {
    let refuse = |why: &str| ApiError::forbidden(field, format!("`{rel}` {why}"));
    if rel.is_empty() || rel.chars().any(|c| c.is_control()) {
        return Err(ApiError::bad(field, "must be a path relative to --root, without control characters".into()));
    }
    let p = Path::new(rel);
    if p.is_absolute() || rel.starts_with('/') || rel.starts_with('\\') {
        return Err(refuse("is absolute: paths are relative to --root"));
    }
    if !p.components().all(|c| matches!(c, Component::Normal(_))) {
        return Err(refuse("leaves --root (`..` and `.` are refused)"));
    }
    if p.components().next().is_some_and(|c| c.as_os_str() == RUNS) {
        return Err(refuse("is in the runs folder"));
    }
    let full = root.join(p);
    let mut existing = full.clone();
    while !existing.exists() {
        if !existing.pop() {
            break;
        }
    }
    let canon = existing.canonicalize().map_err(|e| ApiError::bad(field, format!("`{rel}`: {e}")))?;
    if !canon.starts_with(root) {
        return Err(refuse("leads outside --root through a symbolic link"));
    }
    Ok(full)
}

/// A spec error as the command line words it, with the field it names.
pub fn spec_error(kind: SpecErrorKind) -> ApiError {
    ApiError::invalid(kind.field(), kind.to_string())
}

/// Parses a spec sent as JSON (the page's form of it), naming the field of a type error.
pub fn parse_spec(value: serde_json::Value) -> Result<Spec, ApiError> {
    let spec: Spec = serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        ApiError::invalid((path != ".").then_some(path), format!("{}", e.inner()))
    })?;
    spec.check_values().map_err(spec_error)?;
    Ok(spec)
}

/// Resolves a spec against its mesh (mesh files relative to the root), as `netspec solve` does.
pub fn resolve(spec: &Spec, root: &Path, max_cells: usize) -> Result<Problem, ApiError> {
    if let Some(file) = &spec.mesh.file {
        under_root(root, &file.to_string_lossy(), "mesh.file")?;
    }
    spec.resolve_within(root, max_cells).map_err(spec_error)
}

/// The spec's picture and where its vertices and edges are in it (for clicking).
#[derive(Serialize)]
pub struct View {
    /// The picture.
    pub svg: String,
    /// Each vertex's picture coordinates.
    pub points: Vec<[f64; 2]>,
    /// Each edge's vertices.
    pub edges: Vec<[u32; 2]>,
}

/// Draws a resolved spec without a design.
pub fn view(p: &Problem) -> View {
    let scene = mesh_scene(p);
    let sinks = p.is_sink.iter().filter(|&&s| s).count();
    let caption = Caption {
        name: if p.spec.description.is_empty() { p.spec.name.clone() } else { p.spec.description.clone() },
        solver: format!("{} vertices, {} edges, {sinks} sinks", p.mesh.num_vertices(), p.mesh.num_edges()),
        status: "not solved".into(),
        objective: None,
        gap: None,
        verdict: "spec".into(),
    };
    View { svg: svg(&scene, &caption), points: picture_points(&scene), edges: scene.edges }
}

/// A new spec on a generated mesh: a `width × height` grid, its boundary the sinks, or a disc
/// (a grid clipped to a circle) or an L shape of that size.
pub fn new_spec(width: usize, height: usize, shape: &str) -> Result<serde_json::Value, ApiError> {
    if !(1..=100).contains(&width) || !(1..=100).contains(&height) {
        return Err(ApiError::invalid(Some("width".into()), "width and height must be 1 to 100 cells".into()));
    }
    let (w, h) = (width as f64, height as f64);
    let mesh = match shape {
        "grid" => serde_json::json!({ "grid": { "width": width, "height": height, "spacing": 1.0 } }),
        "disc" => {
            let outer: Vec<[f64; 2]> = (0..48)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 48.0;
                    [w / 2.0 * (1.0 + a.cos()), h / 2.0 * (1.0 + a.sin())]
                })
                .collect();
            serde_json::json!({ "clipped": { "outer": outer, "spacing": 1.0 } })
        }
        "L" => {
            let outer = [
                [0.0, 0.0],
                [w, 0.0],
                [w, (h / 2.0).ceil()],
                [(w / 2.0).ceil(), (h / 2.0).ceil()],
                [(w / 2.0).ceil(), h],
                [0.0, h],
            ];
            serde_json::json!({ "clipped": { "outer": outer, "spacing": 1.0 } })
        }
        other => {
            return Err(ApiError::invalid(Some("shape".into()), format!("`{other}`: expected grid, disc or L")));
        }
    };
    Ok(serde_json::json!({
        "name": format!("new-{shape}-{width}x{height}"),
        "description": "",
        "mesh": mesh,
        "sinks": { "all_boundary": true },
        "coverage": { "range": 2 },
        "weights": { "length": 1, "distance": 1 },
        "solver": { "name": "highs", "time_limit": 10 },
    }))
}
