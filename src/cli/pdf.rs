//! Printing an HTML page to PDF with headless Chromium: the `.pdf` outputs of
//! `drawing` (the sheet's SVG on a page of the sheet's size) and `calc` (the
//! calculation report) both go through here.

use std::path::Path;

use vesselcad::drawing::chromium::{CHROMIUM, headless};

/// Prints the HTML `page` to `out` as PDF (the page's own `@page` rule sets the
/// paper). `instead` names the extension to write when Chromium is missing.
pub fn print_html(page: &str, out: &Path, instead: &str) -> Result<(), String> {
    if !Path::new(CHROMIUM).exists() {
        return Err(format!(
            "{CHROMIUM} is not installed (Debian: apt-get install chromium); write {instead} instead"
        ));
    }
    let dir = std::env::temp_dir().join(format!(
        "vesselcad-pdf-{}-{}",
        std::process::id(),
        out.file_stem().and_then(|s| s.to_str()).unwrap_or("page")
    ));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let html = dir.join("page.html");
    std::fs::write(&html, page).map_err(|e| e.to_string())?;
    let target = std::path::absolute(out).map_err(|e| e.to_string())?;
    std::fs::remove_file(&target).ok();
    let result = headless(&dir.join("profile"))
        .arg("--no-pdf-header-footer")
        .arg(format!("--print-to-pdf={}", target.display()))
        .arg(format!("file://{}", html.display()))
        .output();
    std::fs::remove_dir_all(&dir).ok();
    match result {
        Ok(o) if o.status.success() && target.exists() => Ok(()),
        Ok(o) => Err(format!(
            "chromium could not print {}: {}",
            out.display(),
            String::from_utf8_lossy(&o.stderr)
        )),
        Err(e) => Err(format!("could not run {CHROMIUM}: {e}")),
    }
}
