//! Options of the shape stage ([`super`]) and their defaults.

/// Options of the shape stage.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ShapeOptions {
    /// Relaxation iterations (valence and angle flips, then a tangential relaxation pass).
    /// Default 40 (20 left a mean smallest angle about 0.3 degrees lower; docs/method.md,
    /// "Remesh shape").
    pub relax_iterations: usize,
    /// Polish iterations (angle flips, then a joint area and shape step of every vertex): the
    /// polish also equalizes the areas. Default 85 (100 before the global area steps, which
    /// with 85 gave lower `d_face_relative` on 10 of the 11 shared meshes at about 6% more
    /// time; docs/method.md, "Remesh shape").
    pub polish_iterations: usize,
    /// The polish stops early, after its global area steps, at the first iteration that
    /// flips no edge and moves the vertices by less than this root mean square, in target
    /// edge lengths (0 or less: every polish iteration runs). Default [`DEFAULT_POLISH_TOLERANCE`].
    pub polish_tolerance: f64,
    /// Global area steps (`global_area`): Gauss-Newton steps of the area term over all free
    /// vertices at once, one every 5 polish iterations from the polish's first (0: none).
    /// Default 6 (docs/method.md, "Remesh shape"). A sized remesh makes none (its areas
    /// are covered areas, docs/method.md section 19).
    pub area_steps: usize,
    /// Split long and collapse short edges in the first half of the relaxation
    /// (`resample`), where the map is resolved at the remesh's scale, and split and collapse
    /// by the regions' area error in the second half (`rebalance`). Default on: it raised
    /// the mean smallest angle on 10 of the 11 shared meshes, and the rebalancing halved the
    /// hand's `d_face_relative` (docs/method.md, "Remesh shape").
    pub resample: bool,
    /// Weight `mu` of the shape term against the area term in the polish. Default
    /// [`DEFAULT_SHAPE_WEIGHT`]. A sized remesh weighs the shape term
    /// [`COVERED_SHAPE_WEIGHT`] at the default, in proportion to this otherwise (its areas are
    /// covered areas, docs/method.md section 19).
    pub shape_weight: f64,
    /// Sweeps of the pure-area equalization after the shape stage. Default 0: they lowered the
    /// mean smallest angle by 2-3 degrees for the area the polish gains as well.
    pub area_sweeps: usize,
    /// The crease bound (degrees): the largest angle between the normals of the two faces of
    /// a flipped edge after the flip, unless the old pair was bent more (sharper edges are
    /// creases and are kept), and the bend of the input edges [`ShapeOptions::creases`] puts
    /// vertices on. Default [`DEFAULT_CREASE_DEG`].
    pub crease_deg: f64,
    /// Face sizing (`remesh::sizing`): uniform (the default), surface or curvature-adapted.
    /// A sized remesh measures its faces by the surface they cover rather than by their
    /// chords (docs/method.md section 19, "Covered areas").
    pub sizing: crate::remesh::sizing::Sizing,
    /// Whether vertices are put on the input's creases (edges bent by more than the crease
    /// bound, in chains of at least 3 edge lengths) and joined by edges (`crease`). Default
    /// [`Creases::Auto`]: with curvature sizing only (docs/method.md, "21. Creases").
    pub creases: Creases,
}

/// Whether the shape stage puts vertices on the input's creases ([`ShapeOptions::creases`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum Creases {
    /// Kept by a curvature-sized remesh (fidelity is what it is for: lower or equal surface
    /// distances on all eleven shared meshes), not by the others (the default).
    #[default]
    #[serde(rename = "auto")]
    Auto,
    /// Kept: a lower surface distance on surfaces with sharp edges (the lung lobe's more than
    /// halved at uniform sizing), worse angles where a segmentation's steps are taken for
    /// creases.
    #[serde(rename = "keep")]
    Keep,
    /// Not kept.
    #[serde(rename = "off")]
    Off,
}

crate::named::named_enum!(Creases, "crease handling", Auto => "auto", Keep => "keep", Off => "off");

impl Default for ShapeOptions {
    fn default() -> Self {
        Self { relax_iterations: 40, polish_iterations: 85, polish_tolerance: DEFAULT_POLISH_TOLERANCE, area_steps: 6, resample: true, shape_weight: DEFAULT_SHAPE_WEIGHT, area_sweeps: 0, crease_deg: DEFAULT_CREASE_DEG, sizing: crate::remesh::sizing::Sizing::Uniform, creases: Creases::Auto }
    }
}

impl ShapeOptions {
    /// Set [`ShapeOptions::relax_iterations`].
    pub fn with_relax_iterations(mut self, n: usize) -> Self {
        self.relax_iterations = n;
        self
    }
    /// Set [`ShapeOptions::polish_iterations`].
    pub fn with_polish_iterations(mut self, n: usize) -> Self {
        self.polish_iterations = n;
        self
    }
    /// Set [`ShapeOptions::polish_tolerance`] (0: no early stop).
    pub fn with_polish_tolerance(mut self, tolerance: f64) -> Self {
        self.polish_tolerance = tolerance;
        self
    }
    /// Set [`ShapeOptions::area_steps`].
    pub fn with_area_steps(mut self, n: usize) -> Self {
        self.area_steps = n;
        self
    }
    /// Set [`ShapeOptions::resample`].
    pub fn with_resample(mut self, on: bool) -> Self {
        self.resample = on;
        self
    }
    /// Set [`ShapeOptions::shape_weight`].
    pub fn with_shape_weight(mut self, mu: f64) -> Self {
        self.shape_weight = mu;
        self
    }
    /// Set [`ShapeOptions::area_sweeps`].
    pub fn with_area_sweeps(mut self, n: usize) -> Self {
        self.area_sweeps = n;
        self
    }
    /// Set [`ShapeOptions::sizing`].
    pub fn with_sizing(mut self, sizing: crate::remesh::sizing::Sizing) -> Self {
        self.sizing = sizing;
        self
    }
    /// Set [`ShapeOptions::creases`].
    pub fn with_creases(mut self, creases: Creases) -> Self {
        self.creases = creases;
        self
    }
    /// Set [`ShapeOptions::crease_deg`].
    pub fn with_crease_deg(mut self, deg: f64) -> Self {
        self.crease_deg = deg;
        self
    }
    /// `deg` when it is a crease bound [`ShapeOptions::crease_deg`] can take (degrees strictly
    /// between 0 and 180), else the reason it is not: the command line, the C ABI and Python
    /// check their value with it.
    pub fn checked_crease_deg(deg: f64) -> Result<f64, String> {
        if deg > 0.0 && deg < 180.0 {
            Ok(deg)
        } else {
            Err(format!("{deg} is not an angle in degrees strictly between 0 and 180"))
        }
    }
    /// `Ok` unless a field is out of its range, else the field, its value and the range: the
    /// shape weight a finite number >= 0, the polish tolerance a number (not NaN, not
    /// infinite), the crease bound as [`ShapeOptions::checked_crease_deg`] says, a curvature
    /// sizing's strength finite and > 0. [`remesh`](crate::remesh::remesh) refuses options
    /// that fail it: a NaN weight or bound would otherwise give a remesh silently unshaped.
    pub fn check(&self) -> Result<(), String> {
        if !(self.shape_weight.is_finite() && self.shape_weight >= 0.0) {
            return Err(format!("shape_weight = {} is not a finite number >= 0", self.shape_weight));
        }
        if !self.polish_tolerance.is_finite() {
            return Err(format!("polish_tolerance = {} is not a finite number (0 or less: every polish iteration runs)", self.polish_tolerance));
        }
        Self::checked_crease_deg(self.crease_deg).map_err(|e| format!("crease_deg = {e}"))?;
        match self.sizing {
            crate::remesh::sizing::Sizing::Curvature { strength } if !(strength.is_finite() && strength > 0.0) => {
                Err(format!("the curvature sizing's strength = {strength} is not a finite number > 0 (3 by default)"))
            }
            _ => Ok(()),
        }
    }
    /// Whether the stage puts vertices on the input's creases: [`Creases::Auto`] does with
    /// curvature sizing.
    pub fn keeps_creases(&self) -> bool {
        match self.creases {
            Creases::Auto => matches!(self.sizing, crate::remesh::sizing::Sizing::Curvature { .. }),
            Creases::Keep => true,
            Creases::Off => false,
        }
    }
}

/// The default crease bound ([`ShapeOptions::crease_deg`]): flips that would bend a pair of
/// faces more are refused, and kept creases are input edges bent more. Curvature sizing keeps
/// it: at 45 degrees the bunny's and the lung lobe's distances fell by 3-5% but two FreeSurfer
/// cortices' rose by 3-5% (docs/method.md section 21, "Curvature sizing keeps creases").
pub const DEFAULT_CREASE_DEG: f64 = 60.0;

/// The default [`ShapeOptions::polish_tolerance`]: a thousandth of an edge. On the shared
/// meshes the polish then stops 20 to 40 iterations early on 8 of the 11 and their figures
/// move by a few percent of themselves at most (`d_face_relative` up to 6% higher, the mean
/// smallest angle within 0.1 degree; docs/method.md section 18, "Polish convergence").
pub const DEFAULT_POLISH_TOLERANCE: f64 = 1e-3;

/// The default [`ShapeOptions::shape_weight`]: 0.1 gave both lower `d_face_relative` and a
/// higher mean smallest angle than 0.3 on the shared meshes; since the global area steps
/// follow the surface's areas through the inverse map's differential and move every vertex
/// at once, the areas come out more equal and 0.13 buys a higher mean smallest angle on 9 of
/// the 11 (docs/method.md section 18, "Global area steps through the differential").
pub const DEFAULT_SHAPE_WEIGHT: f64 = 0.13;

/// The shape weight of a sized remesh (faces measured by the surface they cover) at the
/// default [`ShapeOptions::shape_weight`], scaled with it: covered areas and chord shapes pull
/// apart where the remesh bridges a fold, and at the uniform weight of 0.1 the sized
/// remeshes' mean smallest angle fell to 45.8-46.8 degrees on six shared meshes; at 1 it is
/// 46.8-48.5 there with the same surface distances (docs/method.md section 19).
pub const COVERED_SHAPE_WEIGHT: f64 = 1.0;
