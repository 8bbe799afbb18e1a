// MPI for campaigns spread over ranks (`mpirun -n K repose calibrate PLAN.toml`). MPI is
// initialised only when the process was launched by mpirun (OMPI_COMM_WORLD_SIZE or PMI_SIZE
// set), so the plain binary never depends on an MPI runtime being able to start.
#pragma once
#include <string>
#include <vector>

namespace repose::calibrate {

class MpiSession {
 public:
  MpiSession();   // MPI_Init_thread (funneled) under mpirun; nothing otherwise
  ~MpiSession();  // rank 0: stops every simulating rank; then MPI_Finalize when initialised
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool has_workers() const { return active_ && size_ > 1; }

  // Rank 0's bookkeeping of the simulating ranks: those that asked for work when there was
  // none wait here until the next batch or the end.
  std::vector<int>& idle_ranks() { return idle_ranks_; }
  // Rank 0: answers every rank's next request with stop (idempotent).
  void stop_workers();

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
  std::vector<int> idle_ranks_;
  bool stopped_ = false;
};

// Message tags between rank 0 (which owns the database) and the simulating ranks.
enum MpiTag : int { kTagRequest = 1, kTagJob = 2, kTagStop = 3, kTagResult = 4 };

void mpi_send_text(const std::string& text, int dest, int tag);
// Receives the next message from `source` (MPI_ANY_SOURCE allowed); returns its text.
std::string mpi_receive_text(int source, int tag_filter, int* from, int* tag);
// True when a message is waiting (non-blocking).
bool mpi_message_waiting();

// A simulating rank: asks rank 0 for a job, runs it, sends the result, until told to stop.
void mpi_worker_loop(int rank);

}  // namespace repose::calibrate
