//! Keyword arguments -> the library's options. The names are the CLI's flags with `_` for
//! `-` (`lambda_` for `--lambda`, a Python keyword); values as the CLI takes them (strings
//! for the enums, parsed by the library's own `FromStr`). An unknown name is an error.

use capmesh::param::{OpenInitialMap, PunctureEnd};
use capmesh::refine::Smoothing;
use capmesh::remesh::Optimize;
use capmesh::{ParamOptions, RemeshOptions};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::input;

/// The parameterization options shared by `parameterize` and `remesh` (the CLI's `MapArgs`).
pub const MAP_OPTIONS: [&str; 10] = [
    "initial",
    "lambda_",
    "open_lambda",
    "no_lambda_fallback",
    "smoothing",
    "area_refinement",
    "puncture_end",
    "search_sites",
    "multilevel_above",
    "coarse_vertices",
];
/// The options of `remesh` only.
pub const REMESH_OPTIONS: [&str; 16] = ["area_equalization", "optimize", "relax_iterations", "polish_iterations", "polish_tolerance", "area_steps", "shape_weight", "no_resample", "sizing", "creases", "keep_creases", "crease_angle", "placement", "fill_holes", "no_subdivide", "fine_map"];

fn parsed<T: std::str::FromStr<Err = String>>(value: &Bound<'_, PyAny>) -> PyResult<T> {
    let text: String = value.str()?.extract()?;
    text.parse::<T>().map_err(input)
}

fn number<'py, T: FromPyObject<'py>>(name: &str, value: &Bound<'py, PyAny>) -> PyResult<T> {
    value.extract::<T>().map_err(|_| input(format!("{name} = {value} is not a valid {}", std::any::type_name::<T>())))
}

/// Set one parameterization option; `false` when `name` is not one.
fn set_map_option(options: &mut ParamOptions, name: &str, value: &Bound<'_, PyAny>) -> PyResult<bool> {
    match name {
        "initial" => options.open.initial = parsed::<OpenInitialMap>(value)?,
        "lambda_" | "lambda" => options.closed.flatten.lambda = number(name, value)?,
        "open_lambda" => options.open.lambda = number(name, value)?,
        "no_lambda_fallback" => {
            if number::<bool>(name, value)? {
                options.closed.lambda_fallbacks.clear();
            }
        }
        "smoothing" => options.refinement.smoothing = parsed::<Smoothing>(value)?,
        "area_refinement" => options.refinement.area_refinement = number(name, value)?,
        "puncture_end" => options.closed.puncture_end = parsed::<PunctureEnd>(value)?,
        "search_sites" => options.search.sites = number(name, value)?,
        "multilevel_above" => options.closed.multilevel_above = number(name, value)?,
        "coarse_vertices" => options.closed.coarse_vertices = number(name, value)?,
        _ => return Ok(false),
    }
    Ok(true)
}

fn unknown(name: &str, known: &[&str]) -> PyErr {
    input(format!("unknown option {name:?}; the options are {}", known.join(", ")))
}

/// [`ParamOptions`] of a domain string and keyword arguments.
pub fn param(domain: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<ParamOptions> {
    let mut options = ParamOptions::default().with_domain(domain.parse().map_err(input)?);
    if let Some(kwargs) = kwargs {
        for (key, value) in kwargs.iter() {
            let name: String = key.extract()?;
            if !set_map_option(&mut options, &name, &value)? {
                return Err(unknown(&name, &MAP_OPTIONS));
            }
        }
    }
    Ok(options)
}

/// [`RemeshOptions`] of the grid and keyword arguments.
pub fn remesh(grid: capmesh::CapGrid, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<RemeshOptions> {
    let mut options = RemeshOptions::default().with_grid(grid);
    let Some(kwargs) = kwargs else { return Ok(options) };
    for (key, value) in kwargs.iter() {
        let name: String = key.extract()?;
        if set_map_option(&mut options.param, &name, &value)? {
            continue;
        }
        match name.as_str() {
            "area_equalization" => options.area_equalization = number(&name, &value)?,
            "optimize" => options.optimize = parsed::<Optimize>(&value)?,
            "relax_iterations" => options.shape = options.shape.clone().with_relax_iterations(number(&name, &value)?),
            "polish_iterations" => options.shape = options.shape.clone().with_polish_iterations(number(&name, &value)?),
            "polish_tolerance" => options.shape = options.shape.clone().with_polish_tolerance(number(&name, &value)?),
            "area_steps" => options.shape = options.shape.clone().with_area_steps(number(&name, &value)?),
            "shape_weight" => options.shape = options.shape.clone().with_shape_weight(number(&name, &value)?),
            "no_resample" => options.shape = options.shape.clone().with_resample(!number::<bool>(&name, &value)?),
            "sizing" => options.shape = options.shape.clone().with_sizing(parsed::<capmesh::Sizing>(&value)?),
            "crease_angle" => {
                let deg = capmesh::ShapeOptions::checked_crease_deg(number(&name, &value)?).map_err(|e| input(format!("{name} = {e}")))?;
                options.shape = options.shape.clone().with_crease_deg(deg);
            }
            "creases" => options.shape = options.shape.clone().with_creases(parsed::<capmesh::Creases>(&value)?),
            // The CLI's --keep-creases: True is creases="keep", False leaves the default.
            "keep_creases" => {
                if number::<bool>(&name, &value)? {
                    options.shape = options.shape.clone().with_creases(capmesh::Creases::Keep);
                }
            }
            "placement" => options.placement = parsed::<capmesh::Placement>(&value)?,
            "fill_holes" => options.holes = if number::<bool>(&name, &value)? { capmesh::Holes::Fill } else { capmesh::Holes::Keep },
            "no_subdivide" => options.subdivide_coarse = !number::<bool>(&name, &value)?,
            "fine_map" => options.coarse_map = !number::<bool>(&name, &value)?,
            _ => return Err(unknown(&name, &[&MAP_OPTIONS[..], &REMESH_OPTIONS[..]].concat())),
        }
    }
    Ok(options)
}
