//! `capmesh harmonics`: harmonic representation of one mesh (the paper's adaptive harmonics or
//! the spherical cap harmonics, `--basis`), written as the reconstructed surface (the input's
//! connectivity, or a uniform cap mesh with `--resample-faces`), the coefficients (JSON) and a
//! report of the error per order.

use crate::failure::{self, Failure};
use crate::outputs;
use crate::{read, refuse_overwrite};
use capmesh::cap::Domain;
use capmesh::param::{parameterize, ParamOptions};
use capmesh::harmonics::{analyze_map, basis_degree, BasisKind, HarmonicBasis, HarmonicFit, HarmonicsOptions, HarmonicsOutput};
use capmesh::io;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Arguments of `capmesh harmonics`.
pub struct HarmonicsArgs {
    pub input: PathBuf,
    pub order: usize,
    pub output: PathBuf,
    pub coefficients: Option<PathBuf>,
    pub report: Option<PathBuf>,
    pub cap_mesh: Option<PathBuf>,
    pub domain: Domain,
    pub figures: Option<PathBuf>,
    pub allow_poor_map: bool,
    pub basis: BasisKind,
    pub resample_faces: Option<usize>,
    pub quiet: bool,
}

/// The coefficients file: everything needed to evaluate the representation at a cap point.
#[derive(Serialize)]
struct CoefficientsFile<'a> {
    /// `ah` or `scha`.
    basis: &'static str,
    /// The rim condition of `scha` (`neumann`, `dirichlet`, `mixed`); absent for `ah`.
    #[serde(skip_serializing_if = "Option::is_none")]
    boundary: Option<&'static str>,
    /// What the numbers mean.
    definition: &'static str,
    z_star: f64,
    order: usize,
    /// `ah` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    q1: Option<f64>,
    /// `ah` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    q2: Option<f64>,
    coefficients: Vec<Coefficient>,
    /// The file whose parameterization the coefficients are evaluated on.
    source: &'a str,
}

#[derive(Serialize)]
struct Coefficient {
    n: usize,
    m: isize,
    /// The degree of the function: `n` for `ah`, the non-integer `nu_n^m` for `scha`.
    degree: f64,
    x: f64,
    y: f64,
    z: f64,
}

const BASIS_DOC: &str = "position(X, Y, Z) = sum over 0 <= n <= order, -n <= m <= n of (x, y, z)_nm A_n^m(X, Y, Z), \
     at a point (X, Y, Z) of the unit-sphere cap Z >= z_star (one per vertex in the --cap-mesh file); \
     t = q1 Z + q2, phi = atan2(Y, X); A_n^0 = sqrt(q1 / (2 pi)) Pbar_n^0(t); for m > 0 \
     A_n^m = (-1)^m sqrt(q1 / pi) Pbar_n^m(t) cos(m phi) and A_n^-m = (-1)^m sqrt(q1 / pi) \
     Pbar_n^m(t) sin(m phi); Pbar_n^m = sqrt((2n + 1) / 2 (n - m)! / (n + m)!) P_n^m with \
     P_n^m(x) = (-1)^m / (2^n n!) (1 - x^2)^(m/2) d^(n+m)/dx^(n+m) (x^2 - 1)^n \
     (capmesh::harmonics::basis, paper Eq. 22-24 with q1 = 2 / (1 - z_star))";

const SCHA_DOC: &str = "position(X, Y, Z) = sum over 0 <= n <= order, -n <= m <= n of (x, y, z)_nm S_n^m(X, Y, Z), \
     at a point (X, Y, Z) of the unit-sphere cap Z >= z_star (one per vertex in the --cap-mesh file); \
     theta = acos(Z), phi = atan2(Y, X); S_n^0 = Theta_n^0(theta) / sqrt(2 pi); for m > 0 \
     S_n^m = Theta_n^m(theta) cos(m phi) / sqrt(pi) and S_n^-m = Theta_n^m(theta) sin(m phi) / sqrt(pi); \
     Theta_n^m is proportional to the Legendre function P_degree^-m(cos theta) of the listed non-integer \
     degree, regular at the pole, with integral over [z_star, 1] of Theta^2 d(cos theta) = 1 and positive \
     next to the pole; boundary: neumann dTheta/dtheta = 0 at theta_c = acos(z_star), dirichlet Theta = 0 \
     there, mixed neumann for n - m even and dirichlet for n - m odd; z_star = -1 (a closed surface, whose cap rim \
     is the puncture): no rim, the real spherical harmonics of integer degree (capmesh::harmonics::scha)";

fn coefficients_file<'a>(fit: &HarmonicFit, source: &'a str) -> Result<CoefficientsFile<'a>, String> {
    let basis = fit.basis().map_err(|e| e.to_string())?;
    let (q1, q2, definition) = match &basis {
        HarmonicBasis::Adaptive(b) => (Some(b.q1()), Some(b.q2()), BASIS_DOC),
        HarmonicBasis::SphericalCap(_) => (None, None, SCHA_DOC),
    };
    Ok(CoefficientsFile {
        basis: fit.basis.name(),
        boundary: fit.basis.boundary().map(|b| b.name()),
        definition,
        z_star: fit.z_star,
        order: fit.order,
        q1,
        q2,
        coefficients: fit
            .coefficients
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let (n, m) = basis_degree(i);
                let degree = basis.degree(n, m).unwrap_or(f64::NAN);
                Coefficient { n, m, degree, x: c[0], y: c[1], z: c[2] }
            })
            .collect(),
        source,
    })
}

/// Run `capmesh harmonics`.
pub fn run(args: HarmonicsArgs) -> Result<(), Failure> {
    let input = &args.input;
    refuse_overwrite(input, &args.output)?;
    for extra in [&args.coefficients, &args.report, &args.cap_mesh].into_iter().flatten() {
        refuse_overwrite(input, extra)?;
    }
    let targets: Vec<&Path> = [Some(&args.output), args.coefficients.as_ref(), args.report.as_ref(), args.cap_mesh.as_ref()].into_iter().flatten().map(|p| p.as_path()).collect();
    outputs::refuse_duplicates(&targets)?;
    for mesh_out in [Some(&args.output), args.cap_mesh.as_ref()].into_iter().flatten() {
        if io::Format::from_path(mesh_out).is_none() {
            return Err(Failure::Error(format!(
                "{}: unknown mesh format; use .obj, .ply, .off, .stl, .gii or a FreeSurfer surface name (.pial, .white, ...), optionally .gz",
                mesh_out.display()
            )));
        }
    }
    let mesh = read(input)?;
    let bar = crate::cli_progress::Bar::new(args.quiet);
    let named = |e: capmesh::Error| failure::of_pipeline("harmonics", input, bar.stage(), e);
    let options = HarmonicsOptions::default()
        .with_order(args.order)
        .with_param(ParamOptions::default().with_domain(args.domain))
        .with_basis(args.basis)
        .with_resample_faces(args.resample_faces);
    // Cheap checks first (order, vertex count), then the parameterization, then the fit.
    capmesh::harmonics::pipeline::check_request(&mesh, &options).map_err(|e| named(e.into()))?;
    let map = parameterize(&mesh, &options.param, &bar).map_err(named)?;
    let HarmonicsOutput { reconstructed, fit, resampled, report } = analyze_map(&mesh, &map, &options, &bar).map_err(named)?;
    bar.finish();
    let mut staged = vec![outputs::stage_mesh(&args.output, resampled.as_ref().unwrap_or(&reconstructed))?];
    if let Some(path) = &args.cap_mesh {
        staged.push(outputs::stage_mesh(path, &map.cap_mesh(&mesh))?);
    }
    if let Some(path) = &args.coefficients {
        staged.push(outputs::stage_json(path, &coefficients_file(&fit, &display_name(input))?)?);
    }
    if let Some(path) = &args.report {
        staged.push(outputs::stage_json(path, &report)?);
    }
    outputs::commit(staged, || format!("harmonics of {} stopped while writing", input.display()))?;
    outln!(
        "{}: {} on Z* = {:.4}, {} basis{}, order {} ({} functions), {:.2} s",
        input.display(),
        report.param.kind,
        report.z_star,
        report.basis.name(),
        report.basis.boundary().map(|b| format!(" ({})", b.name())).unwrap_or_default(),
        report.order,
        report.basis_functions,
        report.seconds
    );
    outln!("order  mean error  max error   (relative to the bounding-box diagonal)");
    for e in &report.errors_by_order {
        outln!("{:5}  {:10.6}  {:9.6}", e.order, e.mean_relative, e.max_relative);
    }
    if let Some(b) = report.boundary_max_relative {
        outln!("boundary loop ({} vertices): max error {:.6} of the diagonal at order {}", report.boundary_vertices, b, report.order);
    }
    if let Some(faces) = report.resampled_faces {
        outln!("resampled on a cap mesh of {faces} faces: {}", args.output.display());
    }
    if report.basis == BasisKind::Adaptive {
        outln!(
            "order-1 aspect ratio sigma1/sigma3 {:.4} (exact order-1 ellipsoid {:.4})",
            report.aspect_ratio, report.ellipsoid_aspect_ratio
        );
    } else {
        outln!("order-1 aspect ratio sigma1/sigma3 {:.4}", report.aspect_ratio);
    }
    crate::warn_if_poor(input, &report.param);
    let verdict = crate::refuse_poor(input, &report.param, args.allow_poor_map);
    if let Some(dir) = &args.figures {
        let output = HarmonicsOutput { reconstructed, fit, resampled, report };
        crate::figures_arg::done(capmesh::figures::harmonics_figures(dir, &display_name(input), &mesh, &map, &output, &Default::default()))?;
    }
    verdict
}

fn display_name(path: &Path) -> String {
    path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}
