//! Yang et al. 2013 Fig. 6 as a ratio: the registration distance of the parcels (each face's
//! mean vertex distance from its registered ideal shape, metres) after the full warp, against
//! the initialisation alone (arc-length boundary and mean-value coordinates), over the blocks of
//! a region on which a template matches. The paper reports 1.99 m against 1.20 m (−40 %).

use super::arclength::Block;
use super::arclength::Match;
use super::file::Template;
use super::select::{candidates, Instances};
use super::warp::{warp, ROUNDS};
use crate::layout::field::FieldMethod;
use crate::layout::parcels::{blocks, StreetIndex};
use crate::layout::region::Region;
use crate::layout::split::{Selection, SplitError, SplitOptions};
use crate::layout::tree::split;
use rand::rngs::Xoshiro256PlusPlus;
use rand::SeedableRng;
use serde::Serialize;

/// The measured ratio.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fig6 {
    /// Blocks of the region.
    pub blocks: usize,
    /// Blocks on which some template matches (their best template by full warp is measured).
    pub matched: usize,
    /// Faces measured.
    pub faces: usize,
    /// Mean registration distance with mean-value coordinates only (metres).
    pub mvc: f64,
    /// Mean registration distance after the full warp (metres).
    pub warp: f64,
    /// `warp / mvc`.
    pub ratio: f64,
}

/// The ratio over the region's blocks (its streets from the control loop, `--mode best`, the
/// region's seed).
pub fn fig6(region: &Region, library: &[Template]) -> Result<Fig6, SplitError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(region.seed);
    let s = split(region, &SplitOptions::for_region(region, FieldMethod::Distance, Selection::Best), &mut rng)?;
    let bl = blocks(&region.polygon, &s.streets);
    let index = StreetIndex::new(&s.streets);
    let mut instances = Instances::new(library, region.parcel.depth);
    let (mut matched, mut faces, mut mvc, mut full) = (0, 0, 0.0, 0.0);
    for b in bl.iter().filter(|b| !b.has_holes()) {
        let block = Block::new(b.ring(), &index, region.parcel.depth / 3.0);
        let warped = candidates(&block, &mut instances, ROUNDS, region.block.max_length, "block");
        let Some(best) = warped.iter().min_by(|a, b| a.warp.energy.total_cmp(&b.warp.energy)) else { continue };
        // The same template, units and corner match, initialised only.
        let corners: Vec<f64> = best.instance.corners.iter().map(|&(i, _)| best.warp.s[i]).collect();
        let m = Match { s: corners, distortion: 0.0 };
        let zero = warp(&library[best.template], &best.instance, &block, &m, 0);
        matched += 1;
        faces += best.warp.face_distance.len();
        mvc += zero.face_distance.iter().sum::<f64>();
        full += best.warp.face_distance.iter().sum::<f64>();
    }
    let n = faces.max(1) as f64;
    let (mvc, full) = (mvc / n, full / n);
    Ok(Fig6 { blocks: bl.len(), matched, faces, mvc, warp: full, ratio: if mvc > 0.0 { full / mvc } else { f64::NAN } })
}
