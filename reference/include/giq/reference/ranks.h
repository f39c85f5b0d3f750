#pragma once
// The processes of one render: MPI's world when giq is built with GIQ_WITH_MPI and started by
// an MPI launcher (mpirun, srun), otherwise this process alone. The one place that calls MPI;
// distributed_render.h speaks through it.
//
// MPI is initialised on first use, and only when a launcher's environment says this process
// is one of several (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK), so a plain `giq reference`
// never pays for it. Only the thread that first called world() may call the messaging
// functions (MPI_THREAD_FUNNELED).

#include <optional>
#include <string>

namespace giq::reference {

class Ranks {
 public:
  static const Ranks& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  // The ranks on this machine, this one included (for the threads a rank should use).
  int local_size() const { return local_size_; }
  // Whether this build can run across ranks.
  static bool built_with_mpi();

  struct Message {
    int source = 0;
    int tag = 0;
    std::string bytes;
  };
  void send(int to, int tag, const std::string& bytes) const;
  // The next message from any rank, or nullopt at once when none has arrived.
  std::optional<Message> poll() const;
  // Waits for the next message from rank `from`.
  Message receive(int from) const;
  // Ends every rank of the run with `code` (a failure one rank saw alone would otherwise
  // leave the others waiting for it).
  [[noreturn]] void abort(int code) const;

  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;
  ~Ranks();

 private:
  Ranks();
  int rank_ = 0, size_ = 1, local_size_ = 1;
  bool initialised_ = false;
};

}  // namespace giq::reference
