//! Warped templates (Yang et al. 2013 §4): blocks are parcelled by the template that warps onto
//! them with the least distortion, the row parceller taking the blocks no template fits.
//! A region's `[templates]` table adds a directory of the user's files (`dir`) or leaves the
//! built-in ones out (`builtin = false`: the row parceller alone).
//!
//! * [`file`]: template files (TOML) and the embedded library;
//! * [`instance`]: a template made concrete (its repetition unrolled, shared vertices merged);
//! * [`arclength`]: a block's corners and sides, and the matching of a template's onto them;
//! * [`mvc`]: mean-value coordinates; [`register`]: registration by deformation class;
//! * [`warp`]: the warp itself and its energy; [`select`]: the choice per block and the
//!   parcels, streets and counts it makes; [`fig6`]: the paper's Fig. 6 as a ratio.

pub mod arclength;
pub mod assign;
pub mod fig6;
pub mod file;
pub mod instance;
pub mod model;
pub mod mvc;
pub mod register;
pub mod select;
pub mod warp;

pub use file::{library, parse_template, Template, TemplateError};
pub use select::{parcellate_with_templates, TemplateParcels};
