//! The remeshing metrics as the text table `remesh` and `metrics` print on standard output.

/// Print `q`, one metric a line.
pub(crate) fn print_quality(q: &capmesh::metrics::RemeshMetrics) -> Result<(), String> {
    outln!("faces                      {}", q.faces);
    outln!("d_face                     {:.6e}", q.d_face);
    outln!("d_face_relative            {:.4}", q.d_face_relative);
    outln!("d_surface_vertex           {:.6e} ({:.3e} of the diagonal)", q.d_surface_vertex, q.d_surface_vertex_relative);
    outln!("d_surface_sampled          {:.6e} ({:.3e} of the diagonal)", q.d_surface_sampled, q.d_surface_sampled_relative);
    outln!("min_angle_deg              {:.2}", q.min_angle_deg);
    outln!("zero_area_faces            {}", q.zero_area_faces);
    outln!("mean_min_angle_deg         {:.2}", q.mean_min_angle_deg);
    outln!("faces_angle_below_30       {:.2}%", 100.0 * q.share_faces_angle_below_30);
    outln!("max_angle_deg              {:.2}", q.max_angle_deg);
    outln!("interior_valence_6         {:.2}%", 100.0 * q.share_interior_valence_6);
    outln!("self_intersecting_faces    {} (input {})", q.self_intersecting_faces, q.self_intersecting_faces_input);
    outln!("hausdorff_distance         {:.6e} ({:.3e} of the diagonal)", q.hausdorff_distance, q.hausdorff_distance_relative);
    Ok(())
}
