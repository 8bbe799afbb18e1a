#include "calibrate/mpi_session.h"

#include <mpi.h>

#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "calibrate/run_job.h"

namespace repose::calibrate {

MpiSession::MpiSession() {
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMI_SIZE") && !std::getenv("PMIX_RANK")) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (!active_) return;
  try {
    stop_workers();
  } catch (...) {
  }
  MPI_Finalize();
}

void MpiSession::stop_workers() {
  if (stopped_ || !has_workers() || rank_ != 0) return;
  stopped_ = true;
  int stopped = 0;
  for (int r : idle_ranks_) {
    mpi_send_text("", r, kTagStop);
    ++stopped;
  }
  idle_ranks_.clear();
  while (stopped < size_ - 1) {
    int from = 0, tag = 0;
    mpi_receive_text(MPI_ANY_SOURCE, MPI_ANY_TAG, &from, &tag);  // results in flight are dropped
    if (tag == kTagRequest) {
      mpi_send_text("", from, kTagStop);
      ++stopped;
    }
  }
}

void mpi_send_text(const std::string& text, int dest, int tag) {
  MPI_Send(text.data(), int(text.size()), MPI_CHAR, dest, tag, MPI_COMM_WORLD);
}

std::string mpi_receive_text(int source, int tag_filter, int* from, int* tag) {
  MPI_Status status;
  MPI_Probe(source, tag_filter, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::vector<char> buffer(size_t(count) + 1);
  MPI_Recv(buffer.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  if (from) *from = status.MPI_SOURCE;
  if (tag) *tag = status.MPI_TAG;
  return std::string(buffer.data(), size_t(count));
}

bool mpi_message_waiting() {
  int flag = 0;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
  return flag != 0;
}

void mpi_worker_loop(int rank) {
  for (;;) {
    mpi_send_text("", 0, kTagRequest);
    int tag = 0;
    std::string text = mpi_receive_text(0, MPI_ANY_TAG, nullptr, &tag);
    if (tag == kTagStop) return;
    if (tag != kTagJob) throw std::runtime_error("MPI rank " + std::to_string(rank) + ": unexpected message tag " + std::to_string(tag));
    JobOutcome out = execute_job(job_from_text(text), rank);
    mpi_send_text(outcome_to_text(out), 0, kTagResult);
  }
}

}  // namespace repose::calibrate
