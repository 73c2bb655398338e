//! The bytes of the messages islands send each other: little-endian numbers, fitness
//! values as their bits, genomes as their words (checked when read).

use super::exchange::ExchangeError;
use crate::derive::Grammar;
use crate::genome::Genome;
use crate::genome::validate::validate_words;

/// Writes a message.
#[derive(Default)]
pub(super) struct Writer(Vec<u8>);

impl Writer {
    pub(super) fn u64(&mut self, v: u64) -> &mut Self {
        self.0.extend_from_slice(&v.to_le_bytes());
        self
    }

    pub(super) fn f64(&mut self, v: f64) -> &mut Self {
        self.u64(v.to_bits())
    }

    /// A count, then the values.
    pub(super) fn f64s(&mut self, values: &[f64]) -> &mut Self {
        self.u64(values.len() as u64);
        values.iter().for_each(|&v| {
            self.f64(v);
        });
        self
    }

    pub(super) fn genome<G>(&mut self, genome: &Genome<G>) -> &mut Self {
        self.u64(u64::from(genome.len))
            .u64(genome.words.len() as u64);
        for w in &genome.words {
            self.0.extend_from_slice(&w.to_le_bytes());
        }
        self
    }

    /// A count, then the genomes.
    pub(super) fn genomes<'a, G: 'a>(
        &mut self,
        genomes: impl ExactSizeIterator<Item = &'a Genome<G>>,
    ) -> &mut Self {
        self.u64(genomes.len() as u64);
        genomes.for_each(|g| {
            self.genome(g);
        });
        self
    }

    pub(super) fn finish(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.0)
    }
}

/// Reads a message written by [`Writer`]; every read fails cleanly on a message that is
/// short or malformed.
pub(super) struct Reader<'a>(&'a [u8]);

impl<'a> Reader<'a> {
    pub(super) fn new(bytes: &'a [u8]) -> Self {
        Reader(bytes)
    }

    fn take(&mut self, n: usize) -> Result<&'a [u8], ExchangeError> {
        if self.0.len() < n {
            return Err(ExchangeError(format!(
                "a message ended {} bytes early",
                n - self.0.len()
            )));
        }
        let (head, rest) = self.0.split_at(n);
        self.0 = rest;
        Ok(head)
    }

    pub(super) fn u64(&mut self) -> Result<u64, ExchangeError> {
        let bytes = self.take(8)?;
        Ok(u64::from_le_bytes(bytes.try_into().expect("8 bytes")))
    }

    pub(super) fn f64(&mut self) -> Result<f64, ExchangeError> {
        self.u64().map(f64::from_bits)
    }

    /// A count, with each item at least `min_bytes` long: a count the message cannot
    /// hold is refused before anything is allocated for it.
    fn count(&mut self, min_bytes: usize) -> Result<usize, ExchangeError> {
        let n = self.u64()?;
        match usize::try_from(n) {
            Ok(n) if n.saturating_mul(min_bytes) <= self.0.len() => Ok(n),
            _ => Err(ExchangeError(format!(
                "a message announces {n} items but holds {} bytes",
                self.0.len()
            ))),
        }
    }

    pub(super) fn f64s(&mut self) -> Result<Vec<f64>, ExchangeError> {
        let n = self.count(8)?;
        (0..n).map(|_| self.f64()).collect()
    }

    pub(super) fn genome<G: Grammar>(&mut self) -> Result<Genome<G>, ExchangeError> {
        let len = u32::try_from(self.u64()?)
            .map_err(|_| ExchangeError("a genome's gene count is out of range".into()))?;
        let n = self.count(4)?;
        let words: Vec<u32> = self
            .take(n * 4)?
            .chunks_exact(4)
            .map(|w| u32::from_le_bytes(w.try_into().expect("4 bytes")))
            .collect();
        validate_words::<G>(&words, len)
            .map_err(|err| ExchangeError(format!("a genome in a message is invalid: {err}")))?;
        Ok(Genome::from_parts(words, len))
    }

    pub(super) fn genomes<G: Grammar>(&mut self) -> Result<Vec<Genome<G>>, ExchangeError> {
        let n = self.count(16)?;
        (0..n).map(|_| self.genome()).collect()
    }

    /// Fails unless the whole message was read.
    pub(super) fn end(self) -> Result<(), ExchangeError> {
        if self.0.is_empty() {
            Ok(())
        } else {
            Err(ExchangeError(format!(
                "a message holds {} bytes more than expected",
                self.0.len()
            )))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::run::stream;

    crate::prelude::generator! {
        /// A chain of blocks, each with a parameter, so that messages carry parameter
        /// words.
        pub Chain {
            axiom Seg;
            node Seg {
                params { w: f32 ~ uniform(0.5, 2.0) }
                children { next: Seg = 0.5 }
                derive(s) { s.emit(crate::geometry::CUBE); if let Some(n) = next { s.derive(n); } }
            }
        }
    }

    #[test]
    fn what_is_written_reads_back_and_damage_is_refused() {
        let mut ops =
            crate::ops::Operators::<Chain>::new(crate::genome::Limits::new(1, 20, 20).unwrap())
                .unwrap();
        let genomes: Vec<Genome<Chain>> = (0..3)
            .map(|i| ops.random(2 + i, &mut stream(1, 0, i.into())))
            .collect();
        let fitness = [1.5, f64::NAN, f64::NEG_INFINITY];
        let bytes = Writer::default()
            .genomes(genomes.iter())
            .f64s(&fitness)
            .u64(9)
            .finish();
        let mut r = Reader::new(&bytes);
        assert_eq!(r.genomes::<Chain>().unwrap(), genomes);
        let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&r.f64s().unwrap()), bits(&fitness));
        assert_eq!(r.u64().unwrap(), 9);
        r.end().unwrap();

        // Cut short anywhere, or with a word changed into an unknown node kind: an error.
        for n in [0, 7, 8, bytes.len() / 2, bytes.len() - 1] {
            let mut r = Reader::new(&bytes[..n]);
            let read = r
                .genomes::<Chain>()
                .and_then(|_| r.f64s())
                .and_then(|_| r.u64());
            assert!(read.is_err(), "{n} bytes");
        }
        let mut bad = bytes.clone();
        bad[16..20].copy_from_slice(&77u32.to_le_bytes());
        assert!(Reader::new(&bad).genomes::<Chain>().is_err());
        // A count no message could hold allocates nothing.
        let huge = Writer::default().u64(u64::MAX).finish();
        assert!(Reader::new(&huge).f64s().is_err());
    }
}
