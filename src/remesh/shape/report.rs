//! What the shape stage ([`super`]) did: the report of each remesh.

use super::UncrossReport;

/// The points the shape stage started from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Start {
    /// The uniform cap grid pulled back (near-isotropic already, or its remesh better than
    /// the samples').
    #[default]
    Grid,
    /// An isotropic Poisson-disk sample of the surface (`remesh::sample`, docs/method.md
    /// section 18).
    Sample,
}

/// What the shape stage did.
#[derive(Debug, Clone, Copy, Default, serde::Serialize)]
pub struct ShapeReport {
    /// The points it started from.
    pub start: Start,
    /// Starts whose remesh was made (`remesh::from_cap::from_best_start`: isotropic samples,
    /// then the cap grid, until one meets the quality bar).
    pub starts: usize,
    /// Puncture ends whose map was remeshed: 2 when a closed surface's remesh missed the bar
    /// and the other end's map was remeshed too (`remesh::remesh`, the better kept), 1
    /// otherwise, 0 when the stage did not run.
    pub ends: usize,
    /// Whether the kept remesh was polished again, longer, its areas spread beyond the bar
    /// after the options' polish (`remesh::from_cap::polish_longer`).
    pub longer_polish: bool,
    /// Iterations made.
    pub iterations: usize,
    /// Edge flips over all iterations.
    pub flips: usize,
    /// Edge splits over all iterations.
    pub splits: usize,
    /// Edge collapses over all iterations.
    pub collapses: usize,
    /// Edge splits of the area rebalancing (`rebalance`) in the second half of the
    /// relaxation, where the faces of a region are too large (not counted in `splits`).
    pub rebalance_splits: usize,
    /// Edge collapses of the area rebalancing, where the faces of a region are too small (not
    /// counted in `collapses`).
    pub rebalance_collapses: usize,
    /// Vertices removed at slivers after the last flips and again after the moves for shape
    /// (`sliver`): free ones of valence 3 or 4, and a closed surface's rim vertices merged
    /// along short rim edges.
    pub sliver_removals: usize,
    /// Vertex moves (interior relaxation and boundary slides) over all iterations.
    pub moves: usize,
    /// Moves of the vertices of thin faces after the sliver removals, for shape (`worst`).
    pub angle_moves: usize,
    /// Global area steps solved (`global_area`; a step whose system could not be solved is
    /// skipped and not counted).
    pub area_steps: usize,
    /// Boundary vertices put on the input's corners.
    pub corners_kept: usize,
    /// Whether creases were kept ([`super::ShapeOptions::keeps_creases`]).
    pub keep_creases: bool,
    /// The crease bound used, in degrees ([`super::ShapeOptions::crease_deg`]).
    pub crease_bound_deg: f64,
    /// Vertices put on the input's creases (`crease`, when creases are kept).
    pub crease_vertices: usize,
    /// Pairs of consecutive crease points joined by a remesh edge at the end of the stage.
    pub crease_edges: usize,
    /// Pairs of consecutive crease points, joined or not.
    pub crease_pairs: usize,
    /// Crease vertices freed at faces still thin after the iterations
    /// (`crease::RELEASE_BELOW_DEG`).
    pub crease_released: usize,
    /// The face sizing used.
    pub sizing: crate::remesh::sizing::Sizing,
    /// The remesh's angles before the stage.
    pub before: crate::metrics::angles::AngleQuality,
    /// The remesh's angles after it.
    pub after: crate::metrics::angles::AngleQuality,
    /// The removal of self-crossing faces after the area equalization.
    pub uncross: UncrossReport,
}
