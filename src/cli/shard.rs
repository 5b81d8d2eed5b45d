//! `--shard K/N` of `figures` and `snapshot`: a stable split of a run's figures into N
//! parts, so the jobs of a CI matrix each make one part and the N parts together are the
//! whole, each figure once.

use std::path::{Path, PathBuf};

/// Part `k` (from 1) of `n`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This part, 1 to `n`.
    pub k: usize,
    /// How many parts.
    pub n: usize,
}

/// Parses `K/N` (e.g. `2/3`), 1 ≤ K ≤ N ≤ 1000.
pub fn parse_shard(s: &str) -> Result<Shard, String> {
    let (k, n) = s.split_once('/').ok_or_else(|| format!("`{s}` is not K/N, e.g. 1/2 for the first of two parts"))?;
    let k: usize = k.trim().parse().map_err(|_| format!("K `{k}` is not a whole number"))?;
    let n: usize = n.trim().parse().map_err(|_| format!("N `{n}` is not a whole number"))?;
    if n == 0 || n > 1000 || k == 0 || k > n {
        return Err(format!("`{s}`: K must be 1 to N and N 1 to 1000, e.g. 1/2 and 2/2"));
    }
    Ok(Shard { k, n })
}

impl Shard {
    /// Keeps in `lessons` only this part's figures. The figures of every lesson, named
    /// `LESSON/FIGURE` (the snapshot's path), are sorted and dealt out in turn, so the parts
    /// differ in size by at most one figure and a figure's part depends only on the names.
    pub fn keep(&self, lessons: &mut [(PathBuf, crate::lesson::Lesson)]) {
        let mut ids: Vec<String> = lessons.iter().flat_map(|(p, l)| l.figures.iter().map(move |f| id(p, &f.name))).collect();
        ids.sort();
        ids.dedup();
        let mine: std::collections::HashSet<&String> =
            ids.iter().enumerate().filter(|(i, _)| i % self.n == self.k - 1).map(|(_, s)| s).collect();
        for (p, l) in lessons.iter_mut() {
            l.figures.retain(|f| mine.contains(&id(p, &f.name)));
        }
    }
}

/// `LESSON/FIGURE`, the figure's path under `-o` without `.png`.
fn id(lesson: &Path, figure: &str) -> String {
    format!("{}/{figure}", super::figures::stem(lesson))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_are_parsed_or_refused_with_the_form() {
        assert_eq!(parse_shard("2/3"), Ok(Shard { k: 2, n: 3 }));
        for bad in ["0/3", "4/3", "1/0", "a/2", "2", "1/1001"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_parts_together_are_the_whole_each_figure_once() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
        let files = crate::cli::figures::lesson_files(&[dir]).unwrap();
        let lessons: Vec<(PathBuf, crate::lesson::Lesson)> =
            files.into_iter().map(|p| (p.clone(), crate::lesson::load(&p, &[]).unwrap())).collect();
        let all: Vec<String> = lessons.iter().flat_map(|(p, l)| l.figures.iter().map(move |f| id(p, &f.name))).collect();
        assert!(all.len() > 100);
        for n in [1, 2, 3, 7] {
            let mut seen: Vec<String> = Vec::new();
            let mut sizes = Vec::new();
            for k in 1..=n {
                let mut part = lessons.clone();
                Shard { k, n }.keep(&mut part);
                let ids: Vec<String> = part.iter().flat_map(|(p, l)| l.figures.iter().map(move |f| id(p, &f.name))).collect();
                sizes.push(ids.len());
                seen.extend(ids);
            }
            seen.sort();
            let mut whole = all.clone();
            whole.sort();
            assert_eq!(seen, whole, "{n} parts: together the whole, each once");
            assert!(sizes.iter().max().unwrap() - sizes.iter().min().unwrap() <= 1, "{n} parts: {sizes:?}");
        }
    }
}
