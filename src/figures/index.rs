//! `DIR/index.md`: the figures of one run linked under their titles, after a table of the
//! report's headline numbers. Plain Markdown with relative links, readable as text and
//! rendered by any Markdown viewer.

use super::encode::write_file;
use super::{Figure, FigureError};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Write `dir/index.md` for `figures` under `title`, `headline` as a two-column table.
pub fn write_index(dir: &Path, title: &str, headline: &[(String, String)], figures: &[Figure]) -> Result<PathBuf, FigureError> {
    let mut s = String::new();
    let file = |p: &Path| p.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    // Writing to a String cannot fail.
    let _ = writeln!(s, "# {title}\n");
    if !headline.is_empty() {
        let _ = writeln!(s, "| measure | value |\n|---|---|");
        for (k, v) in headline {
            let _ = writeln!(s, "| {k} | {v} |");
        }
        s.push('\n');
    }
    for f in figures {
        let _ = writeln!(s, "## {}\n", f.title);
        let _ = write!(s, "![{}]({})", f.title, file(&f.png));
        if let Some(svg) = &f.svg {
            let _ = write!(s, " ([SVG]({}))", file(svg));
        }
        let _ = writeln!(s, "\n\n{} ({} x {} px)\n", f.kind.caption(), f.width, f.height);
    }
    let path = dir.join("index.md");
    write_file(&path, s.as_bytes())?;
    Ok(path)
}
