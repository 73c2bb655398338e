//! The processes of `mpirun -n P shapegen run SCENE --islands K`: the island model's
//! [`Exchange`] over MPI's world communicator (the `mpi` feature).

use mpi::Count;
use mpi::collective::CommunicatorCollectives;
use mpi::datatype::PartitionMut;
use mpi::environment::Universe;
use mpi::point_to_point::send_receive_into;
use mpi::topology::{Communicator, SimpleCommunicator};
use mpi::traits::Root;
use shapegen::optimize::islands::{Exchange, ExchangeError};

/// MPI, initialized for this process: the world communicator. Dropping it finalizes MPI.
pub struct World {
    /// Keeps MPI initialized.
    _universe: Universe,
    world: SimpleCommunicator,
}

/// Variables an MPI launcher sets in the processes it starts: OpenMPI's `mpirun`,
/// PMIx (OpenMPI's and Slurm's `srun --mpi=pmix`), and the PMI of MPICH's launchers.
const LAUNCHED: [&str; 3] = ["OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"];

impl World {
    /// Whether an MPI launcher started this process.
    pub fn launched() -> bool {
        LAUNCHED.iter().any(|v| std::env::var_os(v).is_some())
    }

    /// Initializes MPI (collectives are called from the main thread only; the worker
    /// threads score). A process that `mpirun` did not start is a world of one.
    pub fn init() -> anyhow::Result<World> {
        let (universe, _) = mpi::initialize_with_threading(mpi::Threading::Funneled)
            .ok_or_else(|| anyhow::anyhow!("MPI was already initialized in this process"))?;
        let world = universe.world();
        Ok(World {
            _universe: universe,
            world,
        })
    }

    /// The number of processes.
    pub fn size(&self) -> usize {
        self.world.size() as usize
    }

    /// This process's rank.
    pub fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    /// The island model's exchange over this world.
    pub fn exchange(&self) -> Box<dyn Exchange> {
        Box::new(Ranks {
            world: self.world.duplicate(),
        })
    }

    /// Ends every process of the run, when this one cannot go on (the others would wait
    /// for it forever).
    pub fn abort(&self, code: i32) -> ! {
        self.world.abort(code)
    }
}

/// The island model's exchange between MPI ranks.
struct Ranks {
    world: SimpleCommunicator,
}

/// Byte counts as MPI counts them.
fn count(n: usize) -> Result<Count, ExchangeError> {
    Count::try_from(n).map_err(|_| ExchangeError(format!("a message of {n} bytes is too long")))
}

/// Where each of `counts` starts in one buffer holding them all.
fn displacements(counts: &[Count]) -> Vec<Count> {
    counts
        .iter()
        .scan(0, |at, &n| {
            let start = *at;
            *at += n;
            Some(start)
        })
        .collect()
}

/// `buffer` cut into `counts`.
fn split(buffer: &[u8], counts: &[Count]) -> Vec<Vec<u8>> {
    let mut at = 0;
    counts
        .iter()
        .map(|&n| {
            let part = buffer[at..at + n as usize].to_vec();
            at += n as usize;
            part
        })
        .collect()
}

impl Exchange for Ranks {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn all_gather(&self, mine: Vec<u8>) -> Result<Vec<Vec<u8>>, ExchangeError> {
        let mut counts = vec![0 as Count; self.size()];
        self.world
            .all_gather_into(&count(mine.len())?, &mut counts[..]);
        let total = counts.iter().map(|&n| n as usize).sum();
        let mut buffer = vec![0u8; total];
        let displs = displacements(&counts);
        let mut partition = PartitionMut::new(&mut buffer[..], &counts[..], &displs[..]);
        self.world
            .all_gather_varcount_into(&mine[..], &mut partition);
        Ok(split(&buffer, &counts))
    }

    fn gather(&self, mine: Vec<u8>) -> Result<Option<Vec<Vec<u8>>>, ExchangeError> {
        let root = self.world.process_at_rank(0);
        let n = count(mine.len())?;
        if self.world.rank() != 0 {
            root.gather_into(&n);
            root.gather_varcount_into(&mine[..]);
            return Ok(None);
        }
        let mut counts = vec![0 as Count; self.size()];
        root.gather_into_root(&n, &mut counts[..]);
        let mut buffer = vec![0u8; counts.iter().map(|&n| n as usize).sum()];
        let displs = displacements(&counts);
        let mut partition = PartitionMut::new(&mut buffer[..], &counts[..], &displs[..]);
        root.gather_varcount_into_root(&mine[..], &mut partition);
        Ok(Some(split(&buffer, &counts)))
    }

    fn shift(&self, to_next: Vec<u8>) -> Result<Vec<u8>, ExchangeError> {
        let size = self.world.size();
        let rank = self.world.rank();
        let next = self.world.process_at_rank((rank + 1) % size);
        let previous = self.world.process_at_rank((rank + size - 1) % size);
        let mut n: Count = 0;
        send_receive_into(&count(to_next.len())?, &next, &mut n, &previous);
        let mut received = vec![0u8; usize::try_from(n).unwrap_or(0)];
        send_receive_into(&to_next[..], &next, &mut received[..], &previous);
        Ok(received)
    }
}
