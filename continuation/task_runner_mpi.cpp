#include "continuation/task_runner_mpi.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <thread>

namespace sympathy {

namespace {

enum Tag : int { kReady = 1, kResult, kAborted, kError, kTask, kStop };
constexpr char kSeparator = '\x1f';

bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK");
}

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

std::string encode(std::size_t index, const TaskRow& row) {
  std::string text = std::to_string(index);
  for (const auto& field : row) {
    if (field.find(kSeparator) != std::string::npos)
      throw std::invalid_argument("run_tasks_mpi: a field holds the separator 0x1f");
    text += kSeparator + field;
  }
  return text;
}

std::pair<std::size_t, TaskRow> decode(const std::string& text) {
  TaskRow fields;
  std::size_t from = 0;
  for (std::size_t at; (at = text.find(kSeparator, from)) != std::string::npos; from = at + 1)
    fields.push_back(text.substr(from, at - from));
  fields.push_back(text.substr(from));
  const std::size_t index = std::stoull(fields.front());
  fields.erase(fields.begin());
  return {index, std::move(fields)};
}

void send(const std::string& payload, int destination, int tag) {
  check(MPI_Send(payload.data(), static_cast<int>(payload.size()), MPI_CHAR, destination, tag,
                 MPI_COMM_WORLD),
        "send");
}

TaskRunSummary manage(const MpiSession& session, std::size_t count, const std::vector<bool>& done,
                      const std::function<void(std::size_t, TaskRow&&)>& record,
                      const std::atomic<bool>* stop) {
  Stopwatch clock;
  TaskRunSummary summary;
  summary.tasks = count;
  for (bool d : done) summary.skipped += d ? 1 : 0;
  summary.threads = session.size() - 1;
  std::size_t next = 0;
  int active = session.size() - 1;
  std::exception_ptr error;
  std::string worker_error;
  std::string buffer;
  while (active > 0) {
    // Probe and sleep: a blocking receive would spin on a core the workers need.
    MPI_Status status;
    for (int flag = 0;;) {
      check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "probe");
      if (flag) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    int length = 0;
    check(MPI_Get_count(&status, MPI_CHAR, &length), "count");
    buffer.assign(static_cast<std::size_t>(length), '\0');
    check(MPI_Recv(buffer.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "receive");
    if (status.MPI_TAG == kResult && !error && worker_error.empty()) {
      try {
        auto [index, row] = decode(buffer);
        record(index, std::move(row));
        ++summary.computed;
      } catch (...) {
        error = std::current_exception();
      }
    } else if (status.MPI_TAG == kError && worker_error.empty()) {
      worker_error = "rank " + std::to_string(status.MPI_SOURCE) + ": " + buffer;
    }
    // Every message gets one answer: the next task, or stop.
    while (next < count && !done.empty() && done[next]) ++next;
    const bool go = !error && worker_error.empty() && !(stop && stop->load()) && next < count;
    if (go) {
      const std::uint64_t index = next++;
      check(MPI_Send(&index, 1, MPI_UINT64_T, status.MPI_SOURCE, kTask, MPI_COMM_WORLD), "send");
    } else {
      send("", status.MPI_SOURCE, kStop);
      --active;
    }
  }
  if (error) std::rethrow_exception(error);
  if (!worker_error.empty()) throw std::runtime_error(worker_error);
  summary.interrupted = summary.skipped + summary.computed < count;
  summary.seconds = clock.seconds();
  return summary;
}

TaskRunSummary serve(const std::function<std::optional<TaskRow>(std::size_t)>& work) {
  Stopwatch clock;
  TaskRunSummary summary;
  send("", 0, kReady);
  for (;;) {
    std::uint64_t index = 0;
    MPI_Status status;
    check(MPI_Recv(&index, 1, MPI_UINT64_T, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status), "receive");
    if (status.MPI_TAG == kStop) break;
    try {
      const auto row = work(index);
      if (row) {
        send(encode(index, *row), 0, kResult);
        ++summary.computed;
      } else {
        send("", 0, kAborted);
      }
    } catch (const std::exception& e) {
      send(e.what(), 0, kError);
    }
  }
  summary.seconds = clock.seconds();
  return summary;
}

}  // namespace

bool mpi_built() {
  return true;
}

MpiSession::MpiSession() {
  if (!launched_by_mpirun()) return;
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "initialization");
  initialized_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  if (initialized_) MPI_Finalize();
}

std::vector<bool> MpiSession::all(bool ok) const {
  if (!initialized_) return {ok};
  const int mine = ok ? 1 : 0;
  std::vector<int> every(static_cast<std::size_t>(size_), 0);
  check(MPI_Allgather(&mine, 1, MPI_INT, every.data(), 1, MPI_INT, MPI_COMM_WORLD), "allgather");
  return {every.begin(), every.end()};
}

void MpiSession::broadcast(std::string& text) const {
  if (!initialized_) return;
  std::uint64_t length = text.size();
  check(MPI_Bcast(&length, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "broadcast");
  text.resize(length);
  check(MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD), "broadcast");
}

TaskRunSummary run_tasks_mpi(const MpiSession& session, std::size_t count,
                             const std::vector<bool>& done,
                             const std::function<std::optional<TaskRow>(std::size_t)>& work,
                             const std::function<void(std::size_t, TaskRow&&)>& record,
                             const std::atomic<bool>* stop) {
  if (session.size() < 2) throw std::invalid_argument("run_tasks_mpi: fewer than two ranks");
  if (!done.empty() && done.size() != count)
    throw std::invalid_argument("run_tasks_mpi: `done` of another size than the tasks");
  return session.rank() == 0 ? manage(session, count, done, record, stop) : serve(work);
}

}  // namespace sympathy
