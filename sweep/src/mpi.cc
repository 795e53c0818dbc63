// The sweep engine's MPI (mpi.h): a thin wrapper over the C API that is
// inert when taebp is built without MPI or not launched by an MPI launcher.
#include "mpi.h"

#include "taebp/sweep/engine.h"

#include <cstdlib>

#ifdef TAEBP_HAVE_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

// A sanitizer build (tools/test --sanitize) ignores what OpenMPI allocates in
// MPI_Init and never frees, and runs an MPI rank's leak check just before
// MPI_Finalize: OpenMPI's plug-ins are unloaded there and its libevent thread
// leaks with "<unknown module>" frames that tools/sanitizers/lsan.supp cannot
// name. Everything the sweep allocated is checked all the same.
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define TAEBP_THIRD_PARTY_ALLOCATIONS __lsan::ScopedDisabler lsan_disabled
#define TAEBP_LEAK_CHECK_NOW() __lsan_do_leak_check()
#else
#define TAEBP_THIRD_PARTY_ALLOCATIONS
#define TAEBP_LEAK_CHECK_NOW()
#endif

namespace taebp::sweep::internal {

bool MpiLaunchDetected() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}

Mpi::Mpi(bool use) {
#ifdef TAEBP_HAVE_MPI
  if (!use) return;
  TAEBP_THIRD_PARTY_ALLOCATIONS;
  MPI_Init(nullptr, nullptr);
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#else
  (void)use;
#endif
}

Mpi::~Mpi() {
#ifdef TAEBP_HAVE_MPI
  if (!active_) return;
  TAEBP_LEAK_CHECK_NOW();
  MPI_Finalize();
#endif
}

void Mpi::Bcast(std::string* s) {
#ifdef TAEBP_HAVE_MPI
  if (!active_) return;
  long n = static_cast<long>(s->size());
  MPI_Bcast(&n, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  s->resize(static_cast<std::size_t>(n));
  MPI_Bcast(s->data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
#else
  (void)s;
#endif
}

void Mpi::Send(const std::string& s, int to, int tag) {
#ifdef TAEBP_HAVE_MPI
  if (!active_) return;
  MPI_Send(s.data(), static_cast<int>(s.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
#else
  (void)s, (void)to, (void)tag;
#endif
}

bool Mpi::Receive(int from, std::string* msg, int* tag, int* source) {
#ifdef TAEBP_HAVE_MPI
  if (!active_) return false;
  int flag = 0;
  MPI_Status st;
  MPI_Iprobe(from < 0 ? MPI_ANY_SOURCE : from, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
  if (!flag) return false;
  int count = 0;
  MPI_Get_count(&st, MPI_CHAR, &count);
  msg->assign(static_cast<std::size_t>(count), '\0');
  MPI_Recv(msg->data(), count, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  *tag = st.MPI_TAG;
  *source = st.MPI_SOURCE;
  return true;
#else
  (void)from, (void)msg, (void)tag, (void)source;
  return false;
#endif
}

void Mpi::Abort(int code) {
#ifdef TAEBP_HAVE_MPI
  if (active_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::_Exit(code);
}

}  // namespace taebp::sweep::internal

namespace taebp::sweep {

bool HaveMpi() {
#ifdef TAEBP_HAVE_MPI
  return true;
#else
  return false;
#endif
}

}  // namespace taebp::sweep
