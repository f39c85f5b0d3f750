#include "giq/reference/ranks.h"

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "giq/base/error.h"

#if GIQ_WITH_MPI
#include <mpi.h>
#endif

namespace giq::reference {

namespace {

// Set by mpirun/mpiexec (Open MPI, MPICH's Hydra) and by Slurm's srun with PMI or PMIx.
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

}  // namespace

bool Ranks::built_with_mpi() { return GIQ_WITH_MPI != 0; }

const Ranks& Ranks::world() {
  static const Ranks ranks;
  return ranks;
}

#if GIQ_WITH_MPI

namespace {
void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
}  // namespace

Ranks::Ranks() {
  if (!launched_by_mpi()) return;
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  initialised_ = true;
  if (provided < MPI_THREAD_FUNNELED) throw std::runtime_error("MPI: the library does not allow threads (MPI_THREAD_FUNNELED)");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  MPI_Comm local;
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local), "MPI_Comm_split_type");
  check(MPI_Comm_size(local, &local_size_), "MPI_Comm_size");
  MPI_Comm_free(&local);
}

Ranks::~Ranks() {
  if (initialised_) MPI_Finalize();
}

void Ranks::send(int to, int tag, const std::string& bytes) const {
  if (bytes.size() > size_t(std::numeric_limits<int>::max())) throw std::runtime_error("MPI: a message over 2 GiB");
  check(MPI_Send(bytes.data(), int(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD), "MPI_Send");
}

namespace {
Ranks::Message receive_probed(const MPI_Status& status) {
  Ranks::Message m;
  m.source = status.MPI_SOURCE;
  m.tag = status.MPI_TAG;
  int count = 0;
  check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
  m.bytes.resize(size_t(count));
  check(MPI_Recv(m.bytes.data(), count, MPI_BYTE, m.source, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  return m;
}
}  // namespace

std::optional<Ranks::Message> Ranks::poll() const {
  int flag = 0;
  MPI_Status status;
  check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
  if (!flag) return std::nullopt;
  return receive_probed(status);
}

Ranks::Message Ranks::receive(int from) const {
  MPI_Status status;
  check(MPI_Probe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &status), "MPI_Probe");
  return receive_probed(status);
}

void Ranks::abort(int code) const {
  std::fflush(stdout);
  std::fflush(stderr);
  if (initialised_) MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

#else

Ranks::Ranks() {
  // Several copies of this build would each render the whole image into the same files.
  const char* n = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (n == nullptr) n = std::getenv("PMI_SIZE");
  if (n != nullptr && std::atoi(n) > 1)
    throw InputError("", "mpirun", std::string("started as one of ") + n + " ranks, but this giq was built without "
                     "GIQ_WITH_MPI; build it with -DGIQ_WITH_MPI=ON (Debian: libopenmpi-dev), or run one process");
}
Ranks::~Ranks() = default;
void Ranks::send(int, int, const std::string&) const { throw std::logic_error("Ranks::send: one rank"); }
std::optional<Ranks::Message> Ranks::poll() const { return std::nullopt; }
Ranks::Message Ranks::receive(int) const { throw std::logic_error("Ranks::receive: one rank"); }
void Ranks::abort(int code) const {
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(code);
}

#endif

}  // namespace giq::reference
