//! Urban street layouts (§5.1 of the paper): a city spec whose major roads split the domain into
//! sub-regions, the level hierarchy (collector roads, local roads on a subdivided mesh,
//! cul-de-sacs) solved per sub-region as network IPs, snake smoothing of the result, city-wide
//! street metrics, and the outputs (picture, GeoJSON, per-level JSON).

pub mod city;
pub mod cluster;
pub mod load;
pub mod major;
pub mod output;
pub mod smooth;
pub mod spec;

pub use city::{run_regions, CityError, CityEvent, CityRunOptions, LevelReport, RegionReport, RegionRoads};
pub use output::{run_city, run_city_on, CityResult};
pub use spec::{CitySpec, CitySpecError, CitySpecErrorKind, LevelSpec, DEFAULT_GEO_ORIGIN};
