//! Reading a city spec as it runs: parsed and checked ([`CitySpec::parse_toml`]), then its
//! `[major]` road network expanded into roads ([`super::major::expand`]).

use super::spec::{CitySpec, CitySpecError, CitySpecErrorKind};
use std::path::Path;

impl CitySpec {
    /// Reads a city TOML file, checks it and expands its major roads.
    pub fn load(path: &Path) -> Result<CitySpec, CitySpecError> {
        let err = |kind| CitySpecError { path: path.to_path_buf(), kind };
        let text = crate::io::read_utf8(path).map_err(|e| err(e.into()))?;
        CitySpec::from_toml(&text).map_err(err)
    }

    /// Parses TOML text, checks it and expands its major roads.
    pub fn from_toml(text: &str) -> Result<CitySpec, CitySpecErrorKind> {
        super::major::expand(CitySpec::parse_toml(text)?)
    }
}
