//! The processes one `shapegen run` is spread over: this one alone, or, in a build with
//! the `mpi` feature, the ranks `mpirun` started, among which the island model shares
//! its islands. Rank 0 prints and writes; an error on any rank ends them all.

use shapegen::optimize::islands::Exchange;
use shapegen::optimize::islands::IslandSettings;
use shapegen::scene::Scene;

/// The processes of this run.
pub struct Processes {
    /// MPI's world, when an MPI launcher started this process.
    #[cfg(feature = "mpi")]
    world: Option<super::mpi::World>,
}

impl Processes {
    /// This process, and the others `mpirun` (or `srun`) started with it, with the `mpi`
    /// feature. MPI is initialized only in a process a launcher started, so that a plain
    /// run does not wait for it.
    pub fn start() -> anyhow::Result<Processes> {
        Ok(Processes {
            #[cfg(feature = "mpi")]
            world: super::mpi::World::launched()
                .then(super::mpi::World::init)
                .transpose()?,
        })
    }

    /// The number of processes.
    pub fn count(&self) -> usize {
        #[cfg(feature = "mpi")]
        return self.world.as_ref().map_or(1, |w| w.size());
        #[cfg(not(feature = "mpi"))]
        1
    }

    /// Whether this process prints and writes the run's files: rank 0.
    pub fn writes(&self) -> bool {
        #[cfg(feature = "mpi")]
        return self.world.as_ref().is_none_or(|w| w.rank() == 0);
        #[cfg(not(feature = "mpi"))]
        true
    }

    /// Checks that `scene` can run on these processes: several need the island model,
    /// with a number of islands they divide.
    pub fn check(&self, scene: &Scene) -> anyhow::Result<()> {
        let n = self.count();
        if n == 1 {
            return Ok(());
        }
        match scene.optimizer.islands {
            Some(islands) if (islands.count as usize).is_multiple_of(n) => Ok(()),
            Some(islands) => anyhow::bail!(
                "--islands {}: the {n} processes must share the islands evenly; give a \
                 multiple of {n}",
                islands.count
            ),
            _ if scene.objectives.is_some() => anyhow::bail!(
                "a run on {n} processes spreads the GA's islands over them, and a scene with \
                 [[objective]] tables is searched by the multi-objective GA, which has none: \
                 run it as one process"
            ),
            _ => anyhow::bail!(
                "a run on {n} processes spreads the GA's islands over them: give --islands K \
                 (a multiple of {n}), or run it as one process"
            ),
        }
    }

    /// The island model's exchange between these processes; `None` for one process
    /// without MPI (the islands then run here alone).
    pub fn exchange(&self) -> Option<Box<dyn Exchange>> {
        #[cfg(feature = "mpi")]
        return self.world.as_ref().map(|w| w.exchange());
        #[cfg(not(feature = "mpi"))]
        None
    }

    /// How the method runs, for the first line of output: `" as 4 islands on 2
    /// processes"`, or nothing for one population.
    pub fn describe(&self, islands: Option<IslandSettings>) -> String {
        match (islands, self.count()) {
            (Some(islands), 1) => format!(" as {} islands", islands.count),
            (Some(islands), n) => format!(" as {} islands on {n} processes", islands.count),
            (None, _) => String::new(),
        }
    }

    /// Ends the command with `outcome`. When the run is spread over several processes
    /// and this one failed, the others would wait for it forever: the error is printed
    /// with the rank, and every process ends.
    pub fn end(self, outcome: anyhow::Result<()>) -> anyhow::Result<()> {
        #[cfg(feature = "mpi")]
        if let (Err(err), Some(world)) = (&outcome, &self.world)
            && world.size() > 1
        {
            // One write, so that the ranks' lines do not interleave.
            let line = format!("error on rank {}: {err:#}\n", world.rank());
            let _ = std::io::Write::write_all(&mut std::io::stderr(), line.as_bytes());
            world.abort(1);
        }
        outcome
    }
}
