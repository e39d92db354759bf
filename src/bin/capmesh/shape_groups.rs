//! `capmesh shape --groups GROUPS.csv`: the cohort comparison of the aspect ratios (the paper's
//! demented vs non-demented study). Reads the `file,group` rows, matches them to the analysed
//! meshes, and prints and writes the per-group summaries and Welch's t-test of every pair
//! (`capmesh::harmonics::cohort`) next to the shape CSV: `NAME.groups.json` and
//! `NAME.groups.csv` for `--csv NAME.csv`.

use capmesh::harmonics::{compare_groups, GroupComparison};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One row of the groups file.
pub struct Assignment {
    /// The file as written in the groups file.
    pub file: String,
    /// Its group.
    pub group: String,
    /// Its line (1-based), for messages.
    pub line: usize,
}

/// The rows of the groups file `path`: `file,group` per line, an optional `file,group` header,
/// blank lines and lines starting with `#` ignored, fields optionally in double quotes.
pub fn read(path: &Path) -> Result<Vec<Assignment>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read the groups file {}: {e}", path.display()))?;
    let mut rows = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields = split_csv(line).map_err(|e| format!("{} line {}: {e}", path.display(), i + 1))?;
        if fields.len() != 2 || fields.iter().any(|f| f.is_empty()) {
            return Err(format!(
                "{} line {}: expected two non-empty fields `file,group`, found {:?}; write one mesh and its group per line",
                path.display(),
                i + 1,
                fields
            ));
        }
        if rows.is_empty() && fields[0].eq_ignore_ascii_case("file") && fields[1].eq_ignore_ascii_case("group") {
            continue;
        }
        rows.push(Assignment { file: fields[0].clone(), group: fields[1].clone(), line: i + 1 });
    }
    if rows.is_empty() {
        return Err(format!("{}: no `file,group` rows", path.display()));
    }
    Ok(rows)
}

/// For each row of `groups`, the index of the mesh among `files` it names: the same path as
/// given on the command line, else the same file name (which must then be unique).
pub fn match_files(groups: &[Assignment], files: &[PathBuf], groups_path: &Path) -> Result<Vec<usize>, String> {
    groups
        .iter()
        .map(|a| {
            if let Some(i) = files.iter().position(|f| f.to_string_lossy() == a.file || Path::new(&a.file) == f.as_path()) {
                return Ok(i);
            }
            let by_name: Vec<usize> = files
                .iter()
                .enumerate()
                .filter(|(_, f)| f.file_name().is_some_and(|n| n.to_string_lossy() == a.file))
                .map(|(i, _)| i)
                .collect();
            match by_name.as_slice() {
                [i] => Ok(*i),
                [] => Err(format!(
                    "{} line {}: '{}' is none of the meshes given to shape; give its path or file name as listed",
                    groups_path.display(),
                    a.line,
                    a.file
                )),
                _ => Err(format!(
                    "{} line {}: '{}' names {} of the meshes given; write its path instead",
                    groups_path.display(),
                    a.line,
                    a.file,
                    by_name.len()
                )),
            }
        })
        .collect()
}

/// Compare the groups with the aspect ratio of each matched mesh (`None` for a failed mesh,
/// left out), print the comparison and write it next to `csv`. Returns the files written.
pub fn compare(groups: &[Assignment], matched: &[usize], ratios: &[Option<f64>], files: &[PathBuf], csv: &Path) -> Result<(PathBuf, PathBuf), String> {
    let mut samples = Vec::new();
    for (a, &i) in groups.iter().zip(matched) {
        match ratios[i] {
            Some(r) => samples.push((a.group.clone(), r)),
            None => eprintln!("warning: {} (group '{}') failed and is left out of the comparison", files[i].display(), a.group),
        }
    }
    let comparison = compare_groups(&samples).map_err(|e| format!("groups comparison: {e}"))?;
    print(&comparison)?;
    let json_path = csv.with_extension("groups.json");
    let csv_path = csv.with_extension("groups.csv");
    let json = serde_json::to_string_pretty(&comparison).map_err(|e| e.to_string())?;
    let json = json + "\n";
    let summary = summary_csv(&comparison);
    let staged = vec![
        capmesh::io::atomic::stage(&json_path, |w| w.write_all(json.as_bytes())).map_err(|e| e.to_string())?,
        capmesh::io::atomic::stage(&csv_path, |w| w.write_all(summary.as_bytes())).map_err(|e| e.to_string())?,
    ];
    capmesh::io::atomic::commit_all(staged).map_err(|e| e.to_string())?;
    outln!("groups comparison written to {} and {}", json_path.display(), csv_path.display());
    Ok((json_path, csv_path))
}

fn print(c: &GroupComparison) -> Result<(), String> {
    outln!("aspect ratio by group (sample standard deviation):");
    outln!("{:<20} {:>5} {:>10} {:>10} {:>10} {:>10}", "group", "n", "mean", "sd", "min", "max");
    for g in &c.groups {
        outln!("{:<20} {:>5} {:>10.5} {:>10.5} {:>10.5} {:>10.5}", g.group, g.count, g.mean, g.std_dev, g.min, g.max);
    }
    for t in &c.tests {
        outln!(
            "Welch's t-test {} vs {}: difference of means {:.5}, t = {:.4}, df = {:.2}, two-sided p = {:.4e}, Cohen's d = {:.3}",
            t.first,
            t.second,
            t.mean_difference,
            t.t,
            t.degrees_of_freedom,
            t.p_value,
            t.cohen_d
        );
    }
    Ok(())
}

/// One row per group, then one per test.
fn summary_csv(c: &GroupComparison) -> String {
    let mut s = String::from("kind,group,other_group,count,mean,std_dev,std_error,min,max,mean_difference,t,degrees_of_freedom,p_value,cohen_d\n");
    for g in &c.groups {
        let _ = writeln!(s, "group,{},,{},{},{},{},{},{},,,,,", quote(&g.group), g.count, g.mean, g.std_dev, g.std_error, g.min, g.max);
    }
    for t in &c.tests {
        let _ = writeln!(
            s,
            "welch,{},{},,,,,,,{},{},{},{},{}",
            quote(&t.first),
            quote(&t.second),
            t.mean_difference,
            t.t,
            t.degrees_of_freedom,
            t.p_value,
            t.cohen_d
        );
    }
    s
}

fn quote(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}

/// Fields of one CSV line (RFC 4180 quotes, no line breaks inside fields), trimmed.
fn split_csv(line: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') if field.trim().is_empty() => {
                field.clear();
                quoted = true;
            }
            (false, ',') => fields.push(std::mem::take(&mut field).trim().to_string()),
            (false, c) => field.push(c),
        }
    }
    if quoted {
        return Err("a quoted field is not closed".into());
    }
    fields.push(field.trim().to_string());
    Ok(fields)
}
