//! A disk that really fills up (ENOSPC on a small tmpfs), as opposed to the file-size limit
//! of tests/hardening.rs, whose signal kills the process: here `run`, `report` and `archive`
//! stay alive, must fail with a message and clean up after themselves. Mounting needs root
//! (as on CI); elsewhere the test says why it did nothing.

use crate::common::{LARGER, TINY, archstudy, leftovers, manifest, run_quiet, scratch, stderr};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A tmpfs of a given size, unmounted when dropped (also when a test fails).
struct SmallDisk(PathBuf);

impl SmallDisk {
    fn mount(at: &Path, kib: u32) -> Option<Self> {
        std::fs::create_dir_all(at).unwrap();
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={kib}k"), "tmpfs"])
            .arg(at)
            .output()
            .is_ok_and(|o| o.status.success());
        ok.then(|| SmallDisk(at.to_path_buf()))
    }

    /// Fills the disk but for about `keep` bytes.
    fn fill_but(&self, keep: u64) {
        let free = fs_free(&self.0);
        let filler = self.0.join("filler");
        let size = free.saturating_sub(keep);
        std::fs::write(&filler, vec![1u8; usize::try_from(size).unwrap()]).unwrap();
    }

    fn empty_filler(&self) {
        let _ = std::fs::remove_file(self.0.join("filler"));
    }
}

impl Drop for SmallDisk {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

/// Free bytes of the file system holding `p` (from `df`, in 1 kB blocks).
fn fs_free(p: &Path) -> u64 {
    let o = Command::new("df")
        .args(["-k", "--output=avail"])
        .arg(p)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    text.lines().nth(1).unwrap().trim().parse::<u64>().unwrap() * 1024
}

#[test]
fn run_report_and_archive_on_a_full_disk_fail_cleanly_and_keep_the_earlier_run() {
    let dir = scratch("disk-full");
    let Some(disk) = SmallDisk::mount(&dir.join("disk"), 4096) else {
        eprintln!("disk_full: cannot mount a tmpfs here (not root?); nothing checked");
        return;
    };
    let out = disk.0.join("out");
    let tiny = manifest(&dir, "tiny.yaml", TINY);
    let o = run_quiet(&tiny, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let earlier = out.join("tiny");
    let results = std::fs::read(earlier.join("results.parquet")).unwrap();
    let report = std::fs::read(earlier.join("report.html")).unwrap();

    // A run whose results and figures do not fit: an error naming the full disk.
    disk.fill_but(600 << 10);
    let larger = manifest(&dir, "larger.yaml", LARGER);
    let o = run_quiet(&larger, &out);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("No space left"), "{}", stderr(&o));
    assert!(std::fs::read(earlier.join("results.parquet")).unwrap() == results);
    assert!(leftovers(&disk.0).is_empty(), "{:?}", leftovers(&disk.0));

    // report with a few kB free: the earlier report stays, no temporary is left.
    disk.empty_filler();
    disk.fill_but(8 << 10);
    let o = archstudy(&["report", earlier.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(std::fs::read(earlier.join("report.html")).unwrap() == report);
    assert!(leftovers(&disk.0).is_empty(), "{:?}", leftovers(&disk.0));

    // archive onto the full disk: no archive, no temporary.
    let a = disk.0.join("run.tar.gz");
    let o = archstudy(&[
        "archive",
        earlier.to_str().unwrap(),
        "-o",
        a.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!a.exists());
    assert!(leftovers(&disk.0).is_empty(), "{:?}", leftovers(&disk.0));

    // With room again, everything works and the run verifies.
    disk.empty_filler();
    let o = archstudy(&[
        "archive",
        earlier.to_str().unwrap(),
        "-o",
        a.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = archstudy(&["verify", a.to_str().unwrap(), "--no-rerun"]);
    assert!(o.status.success(), "{}", stderr(&o));
}
