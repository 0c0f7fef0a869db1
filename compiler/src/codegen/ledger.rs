//! The ledger of the solve's locals: each `let` and each read, recorded as the code is written,
//! so that what a stretch of code declares and reads is asked of it, never found by scanning
//! the text (`scopes` hands a block's locals on by it, an iteration's trial marks what it
//! leaves unread).

use rustc_hash::FxHashSet as HashSet;

/// One entry of the ledger.
#[derive(Clone, Debug)]
enum Entry {
    /// `let name = ..;` written at `depth` (the writer's indent).
    Let { name: String, depth: usize },
    /// A read (or assignment, or move) of local `name`.
    Read(String),
}

/// The locals declared and read, in the order of the text.
#[derive(Clone, Debug, Default)]
pub(super) struct Ledger {
    entries: Vec<Entry>,
}

impl Ledger {
    /// Where the ledger is now: a stretch of code is the entries between two marks.
    pub(super) fn mark(&self) -> usize {
        self.entries.len()
    }

    /// `let name` at `depth`.
    pub(super) fn declare(&mut self, name: &str, depth: usize) {
        self.entries.push(Entry::Let {
            name: name.to_string(),
            depth,
        });
    }

    /// A read of local `name`.
    pub(super) fn read(&mut self, name: &str) {
        self.entries.push(Entry::Read(name.to_string()));
    }

    /// `let`s of `names` at `depth`, written into the text at mark `at` after what follows it
    /// (the declarations a trial turns out to need, put before it).
    pub(super) fn declare_at(&mut self, at: usize, names: &[String], depth: usize) {
        let lets = names.iter().map(|name| Entry::Let {
            name: name.clone(),
            depth,
        });
        self.entries.splice(at..at, lets);
    }

    /// Whether a local was declared after mark `from`.
    pub(super) fn declares_since(&self, from: usize) -> bool {
        (self.entries[from..].iter()).any(|e| matches!(e, Entry::Let { .. }))
    }

    /// The locals declared at `depth` between marks `from` and `to`, in order.
    pub(super) fn lets(&self, from: usize, to: usize, depth: usize) -> Vec<String> {
        (self.entries[from..to].iter())
            .filter_map(|e| match e {
                Entry::Let { name, depth: d } if *d == depth => Some(name.clone()),
                _ => None,
            })
            .collect()
    }

    /// The locals read between marks `from` and `to`.
    pub(super) fn reads(&self, from: usize, to: usize) -> impl Iterator<Item = &str> {
        (self.entries[from..to].iter()).filter_map(|e| match e {
            Entry::Read(name) => Some(name.as_str()),
            _ => None,
        })
    }

    /// The locals declared once after mark `from`, at any depth, and never read after it.
    pub(super) fn unread_since(&self, from: usize) -> Vec<String> {
        let read: HashSet<&str> = self.reads(from, self.mark()).collect();
        let mut seen: HashSet<&str> = HashSet::default();
        let mut twice: HashSet<&str> = HashSet::default();
        for e in &self.entries[from..] {
            if let Entry::Let { name, .. } = e {
                if !seen.insert(name) {
                    twice.insert(name);
                }
            }
        }
        (self.entries[from..].iter())
            .filter_map(|e| match e {
                Entry::Let { name, .. } if !read.contains(name.as_str()) => Some(name),
                _ => None,
            })
            .filter(|name| !twice.contains(name.as_str()))
            .cloned()
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stretch_knows_its_lets_and_reads() {
        let mut l = Ledger::default();
        l.declare("a", 1);
        let from = l.mark();
        l.declare("b", 1);
        l.declare("c", 2);
        l.read("a");
        l.read("c");
        l.declare("d", 1);
        l.declare("d", 1);
        assert_eq!(l.lets(from, l.mark(), 1), ["b", "d", "d"]);
        assert_eq!(l.reads(from, l.mark()).collect::<Vec<_>>(), ["a", "c"]);
        assert_eq!(l.unread_since(from), ["b"]);
        l.declare_at(from, &["e".to_string()], 1);
        assert_eq!(l.lets(0, l.mark(), 1), ["a", "e", "b", "d", "d"]);
    }
}
