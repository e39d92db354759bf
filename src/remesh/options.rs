//! Options of [`remesh`](super::remesh): the cap mesh, what is optimised after the pull-back,
//! where the vertices are put, what is done with several pieces (paper Sec. 4.2 and ours;
//! docs/method.md sections 15, 18 and 22).

use super::shape;
use crate::param::ParamOptions;

/// Which cap mesh to pull back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CapGrid {
    /// Near-equilateral faces of near-equal area, about this many faces. Default 5000.
    Uniform {
        /// Target face count.
        faces: usize,
    },
    /// Latitude rings x longitude sectors with a fan at the pole.
    LatLong {
        /// Rings from the pole to the cap's rim.
        rings: usize,
        /// Meridians.
        sectors: usize,
    },
}

impl Default for CapGrid {
    fn default() -> Self {
        CapGrid::Uniform { faces: 5000 }
    }
}

/// Most cap faces a remesh may ask for: 50 million faces (25 million vertices, several GiB
/// with the metrics' index) is far beyond any anatomical remesh, and an accidental huge count
/// would otherwise run until memory is exhausted.
pub const MAX_GRID_FACES: u64 = 50_000_000;

impl CapGrid {
    /// About how many faces the cap mesh has (the lat/long grid: a fan and two triangles per
    /// quad), saturating instead of overflowing.
    pub fn approximate_faces(&self) -> u64 {
        match *self {
            CapGrid::Uniform { faces } => faces as u64,
            CapGrid::LatLong { rings, sectors } => (sectors as u64).saturating_mul((2 * rings as u64).saturating_sub(1)),
        }
    }
}

/// What is optimised after the pull-back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum Optimize {
    /// Shape (flips and tangential relaxation on the surface, [`shape`]) then the area
    /// equalization: isotropic triangles of near-equal area. The default.
    #[default]
    #[serde(rename = "shape+area")]
    ShapeAndArea,
    /// The area equalization alone: the cap grid's connectivity, near-equal areas.
    #[serde(rename = "area")]
    Area,
    /// The paper's plain pull-back (Sec. 4.2).
    #[serde(rename = "none")]
    None,
}

crate::named::named_enum!(Optimize, "optimisation", ShapeAndArea => "shape+area", Area => "area", None => "none");

/// Where the remesh's vertices are put once its faces are made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum Placement {
    /// Moved along their normals so that the faces fit the surface in the least-squares sense
    /// (docs/method.md section 22): a lower mean distance to the input at the same faces, the
    /// vertices off the surface by a fraction of a face's sagitta. The default.
    #[default]
    #[serde(rename = "fitted")]
    Fitted,
    /// On the input surface, where the inverse map puts them (the paper's pull-back, with
    /// [`Optimize::None`]): the faces are chords of the surface.
    #[serde(rename = "on-surface")]
    OnSurface,
}

crate::named::named_enum!(Placement, "vertex placement", Fitted => "fitted", OnSurface => "on-surface");

/// Options of [`remesh`](super::remesh). Build them from [`RemeshOptions::default`] with the `with_*` setters
/// (or by setting fields): new options may be added without notice.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct RemeshOptions {
    /// The cap mesh. Default uniform with 5000 faces.
    pub grid: CapGrid,
    /// Parameterization options (adaptive cap by default).
    pub param: ParamOptions,
    /// Sweeps of the area equalization of the pulled-back mesh with [`Optimize::Area`] (see
    /// `equalize`; after the shape stage, [`shape::ShapeOptions::area_sweeps`]); 0 pulls
    /// the cap mesh back as the paper does. Default [`DEFAULT_AREA_EQUALIZATION`].
    pub area_equalization: usize,
    /// What is optimised after the pull-back. Default [`Optimize::ShapeAndArea`]; the
    /// latitude/longitude grid keeps its grid lines (its purpose) and gets the area
    /// equalization only.
    pub optimize: Optimize,
    /// The shape stage's options.
    pub shape: shape::ShapeOptions,
    /// What is done with an input in several pieces. Default [`Pieces::DropSpecks`].
    pub pieces: Pieces,
    /// Where the vertices are put at the end. Default [`Placement::Fitted`].
    pub placement: Placement,
    /// What is done with an open surface's holes. Default [`Holes::Keep`].
    pub holes: Holes,
    /// Map a midpoint-subdivided copy of an input that has fewer faces than the uniform
    /// remesh asks for ([`subdivision_levels`](super::subdivision_levels)), and split its
    /// edges longer than the remesh's ([`SPLIT_LONGER_THAN`](super::SPLIT_LONGER_THAN)): the
    /// same surface, its map resolved at the remesh's scale. Default true (docs/method.md
    /// section 25, "Coarse inputs" and "Long edges").
    pub subdivide_coarse: bool,
    /// With the shape stage ([`Optimize::ShapeAndArea`] on the uniform grid), map a closed
    /// input of many more vertices than the remesh needs through a decimated copy sized to
    /// the remesh ([`remesh_copy_vertices`](super::remesh_copy_vertices)) when that is
    /// smaller than the one the parameterization's own options would make: the map is still
    /// prolonged to every input vertex and refined there, so the remesh lies on the input, at
    /// a higher mean |d_area| than `capmesh param`'s. Without the shape stage the map's areas
    /// are the remesh's, and the options' map is made. Default true (docs/method.md section
    /// 20, "Maps sized to the remesh").
    pub coarse_map: bool,
}

/// What [`remesh`](super::remesh) does with the holes of an open surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Holes {
    /// Keep them: an open surface is mapped as a disk and remeshed open. The default.
    #[default]
    Keep,
    /// Fill each with a fan of faces ([`fill_holes`](crate::mesh::holes::fill_holes)) and
    /// remesh the closed surface: for a closed surface with a few faces missing, whose small
    /// boundary a disk's map squeezes (docs/method.md, "Holes"). The remesh is closed.
    Fill,
}

/// What [`remesh`](super::remesh) does with an input made of several pieces (capmesh maps one surface at a
/// time).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Pieces {
    /// Remesh the piece of largest area when the others hold at most
    /// [`DROPPED_AREA_SHARE`](super::DROPPED_AREA_SHARE) of the area (the specks a segmentation leaves); refuse the input
    /// otherwise. The default.
    #[default]
    DropSpecks,
    /// Remesh the piece of largest area whatever the others hold (two lungs or hemispheres
    /// in one file: the larger one), reported as for specks.
    Largest,
}

/// Sweeps of the area equalization by default.
pub const DEFAULT_AREA_EQUALIZATION: usize = 30;

impl RemeshOptions {
    /// Set the cap mesh.
    pub fn with_grid(mut self, grid: CapGrid) -> Self {
        self.grid = grid;
        self
    }

    /// Set the parameterization's options.
    pub fn with_param(mut self, param: ParamOptions) -> Self {
        self.param = param;
        self
    }

    /// Set the sweeps of the area equalization of the pulled-back mesh.
    pub fn with_area_equalization(mut self, area_equalization: usize) -> Self {
        self.area_equalization = area_equalization;
        self
    }

    /// Set what is optimised after the pull-back.
    pub fn with_optimize(mut self, optimize: Optimize) -> Self {
        self.optimize = optimize;
        self
    }

    /// Set the shape stage's options.
    pub fn with_shape(mut self, shape: shape::ShapeOptions) -> Self {
        self.shape = shape;
        self
    }

    /// Set what is done with an input in several pieces.
    pub fn with_pieces(mut self, pieces: Pieces) -> Self {
        self.pieces = pieces;
        self
    }

    /// Set where the vertices are put at the end.
    pub fn with_placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }

    /// Set what is done with an open surface's holes.
    pub fn with_holes(mut self, holes: Holes) -> Self {
        self.holes = holes;
        self
    }

    /// Set whether a coarse input is subdivided for its map ([`RemeshOptions::subdivide_coarse`]).
    pub fn with_subdivide_coarse(mut self, on: bool) -> Self {
        self.subdivide_coarse = on;
        self
    }

    /// `Ok` unless an option is out of its range ([`ParamOptions::check`],
    /// [`shape::ShapeOptions::check`]), else what is wrong with which: what
    /// [`remesh`](super::remesh) checks before it looks at the mesh.
    pub fn check(&self) -> Result<(), String> {
        self.param.check()?;
        self.shape.check()
    }

    /// Set whether a fine closed input is mapped through a copy sized to the remesh
    /// ([`RemeshOptions::coarse_map`]).
    pub fn with_coarse_map(mut self, on: bool) -> Self {
        self.coarse_map = on;
        self
    }
}

impl Default for RemeshOptions {
    fn default() -> Self {
        Self {
            grid: CapGrid::default(),
            param: ParamOptions::default(),
            area_equalization: DEFAULT_AREA_EQUALIZATION,
            optimize: Optimize::default(),
            shape: shape::ShapeOptions::default(),
            pieces: Pieces::default(),
            placement: Placement::default(),
            holes: Holes::default(),
            subdivide_coarse: true,
            coarse_map: true,
        }
    }
}
