// SPDX-License-Identifier: MIT
#include "app/study/ranks.h"

#include <cstdlib>
#include <mutex>

#include "base/error.h"

#ifdef PASTEMIX_HAVE_MPI
#include <mpi.h>
#endif

namespace pastemix::app::study {
namespace {

// Launched by mpirun (Open MPI sets OMPI_COMM_WORLD_SIZE; PMI-based launchers such as srun set PMI_SIZE).
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

#ifdef PASTEMIX_HAVE_MPI
// MPI_THREAD_SERIALIZED: any thread may call MPI, one at a time; this lock makes it one at a time.
std::mutex& mpi_lock() {
  static std::mutex m;
  return m;
}
constexpr int kTag = 21;
#endif

}  // namespace

bool Ranks::built_in() {
#ifdef PASTEMIX_HAVE_MPI
  return true;
#else
  return false;
#endif
}

const Ranks& Ranks::start(bool want_mpi) {
  static Ranks r;
  static bool started = false;
  if (started) return r;
  started = true;
  if (!want_mpi && !launched_by_mpirun()) return r;
#ifdef PASTEMIX_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  if (provided < MPI_THREAD_SERIALIZED)
    throw InputError("--mpi", 0, "", "the MPI library does not allow calls from several threads (MPI_THREAD_SERIALIZED)");
  MPI_Comm_rank(MPI_COMM_WORLD, &r.rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &r.size_);
  r.mpi_ = true;
  std::atexit([] { MPI_Finalize(); });
  return r;
#else
  throw InputError("--mpi", 0, "",
                   "this pastemix is built without MPI (install libopenmpi-dev, scripts/install-deps.sh, and "
                   "rebuild); run the study without --mpi / mpirun, or with --jobs N on one machine");
#endif
}

std::string Ranks::broadcast(const std::string& text) const {
  if (!mpi_) return text;
#ifdef PASTEMIX_HAVE_MPI
  std::lock_guard<std::mutex> g(mpi_lock());
  unsigned long n = text.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  std::string out = root() ? text : std::string(n, '\0');
  if (n > 0) MPI_Bcast(out.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  return out;
#else
  return text;
#endif
}

void Ranks::send_to_root(const std::string& text) const {
#ifdef PASTEMIX_HAVE_MPI
  std::lock_guard<std::mutex> g(mpi_lock());
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, kTag, MPI_COMM_WORLD);
#else
  (void)text;
#endif
}

std::optional<std::string> Ranks::poll() const {
#ifdef PASTEMIX_HAVE_MPI
  std::lock_guard<std::mutex> g(mpi_lock());
  int flag = 0;
  MPI_Status st;
  MPI_Iprobe(MPI_ANY_SOURCE, kTag, MPI_COMM_WORLD, &flag, &st);
  if (!flag) return std::nullopt;
  int n = 0;
  MPI_Get_count(&st, MPI_CHAR, &n);
  std::string out(static_cast<std::size_t>(n), '\0');
  MPI_Recv(out.data(), n, MPI_CHAR, st.MPI_SOURCE, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return out;
#else
  return std::nullopt;
#endif
}

void Ranks::abort(int code) const {
#ifdef PASTEMIX_HAVE_MPI
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace pastemix::app::study
