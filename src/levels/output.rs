//! Outputs: `level.json` (status, layouts, the search's figures — the same bytes for the same
//! seed), `run.json` (what the clock measured), `summary.json` (the annealer
//! over seeds, when asked for) and a picture of every layout
//! (`layout-K.svg` and `.png`: blocks, doors, the graph over them).

use super::spec::{Level, NodeId};
use super::validate::{door, validate};
use super::{Layout, LevelError, LevelOutcome};
use crate::geometry::convex;
use crate::render::{self, level::LevelBlock, level::LevelScene};
use std::path::{Path, PathBuf};

fn put(path: &Path, bytes: &[u8]) -> Result<(), LevelError> {
    std::fs::write(path, bytes)
        .map_err(|e| LevelError::Write { path: path.display().to_string(), reason: e.to_string() })
}

/// Levels with more nodes than this are drawn without node names (at about 640 pixels across
/// they could not be read, and the text is most of the drawing's cost).
pub const LABELS_MAX: usize = 200;

/// The picture of a layout as plain data for [`render::level::level_svg`].
pub fn scene(level: &Level, layout: &Layout, caption: String) -> LevelScene {
    let labels = layout.nodes.len() <= LABELS_MAX;
    let blocks = layout
        .nodes
        .iter()
        .map(|p| {
            let polygon = convex::translate(&level.blocks[p.block.0 as usize].polygon, p.position);
            let n = polygon.len() as f64;
            let centre = polygon.iter().fold([0.0, 0.0], |a, q| [a[0] + q[0] / n, a[1] + q[1] / n]);
            let block = &level.blocks[p.block.0 as usize];
            // A rotation takes its block's colour and says which it is.
            let (shape, label) = match block.rotation_of {
                Some((base, _)) => (base.0 as usize, format!("{} ({})", p.node, block.name)),
                None => (p.block.0 as usize, p.node.clone()),
            };
            LevelBlock { polygon, label: if labels { label } else { String::new() }, shape, centre }
        })
        .collect();
    let v = validate(level, layout);
    let doors = level
        .all_edges()
        .into_iter()
        .filter_map(|e| {
            let (a, b): (NodeId, NodeId) = level.edges[e.0 as usize];
            door(level, &v, e).map(|d| (d, a.0 as usize, b.0 as usize))
        })
        .collect();
    let obstacles = level.obstacles.iter().map(|o| o.polygon.clone()).collect();
    LevelScene { blocks, doors, obstacles, caption }
}

/// What a run measured rather than decided: seconds, and the report of a method that another
/// stopped (`--method both`), whose extent depends on when it was stopped.
const MEASURED: [&str; 5] = ["cspace_time", "time_to_first", "time_to_last", "time_to_proof", "seconds"];

/// Moves every measured value out of `value` into the returned object (same paths), so that
/// `level.json` is the same bytes for the same seed and `run.json` holds the clock's part.
pub fn split_times(value: &mut serde_json::Value) -> serde_json::Value {
    use serde_json::{Map, Value};
    let Value::Object(map) = value else { return Value::Null };
    let mut out = Map::new();
    let stopped = |v: &Value, key: &str| match key {
        "anneal" => v.get("stopped").and_then(Value::as_str) == Some("stopped"),
        "milp" => v.get("note").and_then(Value::as_str) == Some("stopped"),
        _ => false,
    };
    let keys: Vec<String> = map.keys().cloned().collect();
    for k in keys {
        if MEASURED.contains(&k.as_str()) || map.get(&k).is_some_and(|v| stopped(v, &k)) {
            if let Some(v) = map.remove(&k) {
                out.insert(k, v);
            }
        } else if let Some(v) = map.get_mut(&k) {
            let inner = split_times(v);
            if inner.as_object().is_some_and(|o| !o.is_empty()) {
                out.insert(k, inner);
            }
        }
    }
    Value::Object(out)
}

/// Writes the outputs into `dir` (created if missing); returns the files written.
pub fn write(dir: &Path, level: &Level, outcome: &LevelOutcome) -> Result<Vec<PathBuf>, LevelError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| LevelError::Write { path: dir.display().to_string(), reason: e.to_string() })?;
    let json = dir.join("level.json");
    let mut value = serde_json::to_value(outcome)
        .map_err(|e| LevelError::Write { path: json.display().to_string(), reason: e.to_string() })?;
    let times = split_times(&mut value);
    let text = serde_json::to_string_pretty(&value)
        .map_err(|e| LevelError::Write { path: json.display().to_string(), reason: e.to_string() })?;
    put(&json, text.as_bytes())?;
    let run = dir.join("run.json");
    let text = serde_json::to_string_pretty(&times)
        .map_err(|e| LevelError::Write { path: run.display().to_string(), reason: e.to_string() })?;
    put(&run, text.as_bytes())?;
    let mut files = vec![json, run];
    if let Some(summary) = &outcome.seeds {
        let path = dir.join("summary.json");
        let text = serde_json::to_string_pretty(summary)
            .map_err(|e| LevelError::Write { path: path.display().to_string(), reason: e.to_string() })?;
        put(&path, text.as_bytes())?;
        files.push(path);
    }
    for (k, layout) in outcome.layouts.iter().enumerate() {
        let caption = format!("layout {} of {} · door width {}", k + 1, outcome.layouts.len(), level.door_width);
        let svg = render::level::level_svg(&scene(level, layout, caption));
        let svg_path = dir.join(format!("layout-{}.svg", k + 1));
        put(&svg_path, svg.as_bytes())?;
        let png_path = dir.join(format!("layout-{}.png", k + 1));
        let png = render::png(&svg)
            .map_err(|e| LevelError::Write { path: png_path.display().to_string(), reason: e.to_string() })?;
        put(&png_path, &png)?;
        files.extend([svg_path, png_path]);
    }
    Ok(files)
}
