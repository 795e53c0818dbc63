// MPI for the sweep engine: rank 0 owns the output folder; the other ranks
// run their share of the tasks and send each finished task's journal line to
// rank 0. Without MPI (not built with it, or not launched by mpirun) an Mpi is
// one inactive rank of one.
#pragma once

#include <string>

namespace taebp::sweep::internal {

enum Tag { kTagResult = 1, kTagDone = 2, kTagStop = 3 };

// True when an MPI launcher (mpirun, srun) started this process.
bool MpiLaunchDetected();

class Mpi {
 public:
  explicit Mpi(bool use);  // MPI_Init when `use` and built with MPI
  ~Mpi();                  // MPI_Finalize
  Mpi(const Mpi&) = delete;
  Mpi& operator=(const Mpi&) = delete;

  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }

  void Bcast(std::string* s);                       // from rank 0 to all
  void Send(const std::string& s, int to, int tag);
  // A waiting message from `from` (-1: anyone), if any.
  bool Receive(int from, std::string* msg, int* tag, int* source);
  [[noreturn]] void Abort(int code);

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace taebp::sweep::internal
