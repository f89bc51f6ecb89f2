//! Urban layouts by hierarchical domain splitting (Yang, Wang, Vouga, Wonka 2013): a region is
//! split along streamlines of a boundary-aligned cross field, and by warped templates, down to
//! parcels.

pub mod field;
