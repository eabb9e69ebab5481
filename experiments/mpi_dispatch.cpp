// The MPI cell dispatcher (compiled only with BLOCKLAB_MPI; model and guarantees in experiments/cell_dispatch.h):
// rank 0 hands cells out one at a time to whichever rank asks, and computes cells itself on a second thread.
//
// Messages (MPI_COMM_WORLD):
//   worker -> 0  kReady    {previous cell or -1, its status}   "this one is done, give me another"
//   0 -> worker  kAssign   {cell}                              compute it
//   0 -> worker  kStop     {}                                  nothing left: leave run_cells
//   worker -> 0  kFatal    text                                an Error outside a cell; the worker leaves run_cells
//   0 -> worker  kPlan     length-prefixed strings             share()
//   0 -> worker  kReleased {}                                  rank 0 is done with the job (sent by its destructor)
// MPI is initialised with MPI_THREAD_FUNNELED: only the main thread of each rank calls MPI.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "experiments/cell_dispatch.h"
#include "experiments/provenance.h"

namespace blocklab {

namespace {

enum Tag : int { kReady = 1, kAssign = 2, kStop = 3, kFatal = 4, kPlan = 5, kReleased = 6 };

// Waits for a message matching (source, tag) and returns its envelope, sleeping between probes: 20 us at first,
// doubling to at most 1 ms. MPI's blocking receive would spin a core meanwhile.
MPI_Status wait_for_message(int source, int tag) {
  auto pause = std::chrono::microseconds(20);
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
    if (arrived) return status;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(1000));
  }
}

std::string receive_text(const MPI_Status& envelope) {
  int size = 0;
  MPI_Get_count(&envelope, MPI_CHAR, &size);
  std::string text(static_cast<std::size_t>(size), '\0');
  MPI_Recv(text.data(), size, MPI_CHAR, envelope.MPI_SOURCE, envelope.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

void send_text(const std::string& text, int destination, int tag) {
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, destination, tag, MPI_COMM_WORLD);
}

void send_empty(int destination, int tag) { MPI_Send(nullptr, 0, MPI_CHAR, destination, tag, MPI_COMM_WORLD); }

std::string pack_strings(const std::vector<std::string>& values) {
  std::string packed;
  for (const std::string& value : values) packed += std::to_string(value.size()) + ":" + value;
  return packed;
}

std::vector<std::string> unpack_strings(const std::string& packed) {
  std::vector<std::string> values;
  std::size_t at = 0;
  while (at < packed.size()) {
    const std::size_t colon = packed.find(':', at);
    if (colon == std::string::npos) fail("mpi", "malformed plan message from rank 0");
    const std::size_t size = std::stoul(packed.substr(at, colon - at));
    values.push_back(packed.substr(colon + 1, size));
    at = colon + 1 + size;
  }
  return values;
}

class MpiDispatcher final : public CellDispatcher {
 public:
  MpiDispatcher() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
    host_ = host_name();
    // Every rank's host, gathered once for the description (provenance, progress).
    std::vector<char> names(static_cast<std::size_t>(ranks_) * kHostBytes, '\0');
    std::string mine = host_.substr(0, kHostBytes - 1);
    mine.resize(kHostBytes, '\0');
    MPI_Allgather(mine.data(), kHostBytes, MPI_CHAR, names.data(), kHostBytes, MPI_CHAR, MPI_COMM_WORLD);
    for (int r = 0; r < ranks_; ++r) hosts_.emplace_back(names.data() + static_cast<std::size_t>(r) * kHostBytes);
    if (provided < MPI_THREAD_FUNNELED && rank_ == 0) {
      // Rank 0 computes on a second thread while its main thread talks MPI; without FUNNELED it only dispatches.
      compute_on_rank_zero_ = false;
    }
  }

  ~MpiDispatcher() override {
    if (rank_ == 0) {
      for (int r = 1; r < ranks_; ++r) send_empty(r, kReleased);
    } else {
      // Anything rank 0 still sends (a late kStop) is read and dropped until it releases this rank.
      while (!released_) {
        const MPI_Status envelope = wait_for_message(0, MPI_ANY_TAG);
        receive_text(envelope);
        released_ = envelope.MPI_TAG == kReleased;
      }
    }
    MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  bool is_mpi() const override { return true; }

  std::string description() const override {
    std::map<std::string, int> per_host;
    for (const std::string& host : hosts_) ++per_host[host];
    std::string hosts;
    for (const auto& [host, count] : per_host) hosts += (hosts.empty() ? "" : ", ") + host + ": " + std::to_string(count);
    return mpi_library_version() + ", " + std::to_string(ranks_) + (ranks_ == 1 ? " rank" : " ranks") + " on " +
           std::to_string(per_host.size()) + (per_host.size() == 1 ? " host" : " hosts") + " (" + hosts + ")";
  }

  std::vector<std::string> share(const std::function<std::vector<std::string>()>& produce) override {
    if (rank_ == 0) {
      const std::vector<std::string> values = produce();   // on a throw the destructor releases the others
      const std::string packed = pack_strings(values);
      for (int r = 1; r < ranks_; ++r) send_text(packed, r, kPlan);
      return values;
    }
    const MPI_Status envelope = wait_for_message(0, MPI_ANY_TAG);
    const std::string packed = receive_text(envelope);
    if (envelope.MPI_TAG == kReleased) {
      released_ = true;
      throw RankZeroFailed();
    }
    return unpack_strings(packed);
  }

  void run_cells(const std::vector<std::size_t>& pending, const CellRunner& run_cell,
                 const CellEvents& events) override {
    if (ranks_ == 1) {
      CellDispatcher::run_cells(pending, run_cell, events);
    } else if (rank_ == 0) {
      coordinate(pending, run_cell, events);
    } else {
      work(run_cell);
    }
  }

  void abort_job_for(const std::string& message) override {
    if (rank_ == 0) return;
    std::fprintf(stderr, "blocklab: error: rank %d on %s: %s\n", rank_, host_.c_str(), message.c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }

 private:
  static constexpr int kHostBytes = 256;

  // A rank other than 0: ask for a cell, run it, report it with the next request, until told to stop.
  void work(const CellRunner& run_cell) {
    long long report[2] = {-1, 0};
    for (;;) {
      MPI_Send(report, 2, MPI_LONG_LONG, 0, kReady, MPI_COMM_WORLD);
      const MPI_Status envelope = wait_for_message(0, MPI_ANY_TAG);
      if (envelope.MPI_TAG != kAssign) {
        receive_text(envelope);
        released_ = envelope.MPI_TAG == kReleased;
        return;
      }
      long long cell = 0;
      MPI_Recv(&cell, 1, MPI_LONG_LONG, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      CellStatus status = CellStatus::error;
      try {
        status = run_cell(static_cast<std::size_t>(cell));
      } catch (const std::exception& e) {
        send_text(e.what(), 0, kFatal);
        return;
      }
      report[0] = cell;
      report[1] = status == CellStatus::ok ? 0 : 1;
    }
  }

  // Rank 0: the main thread serves requests and reports events; a second thread takes cells from the same queue.
  void coordinate(const std::vector<std::size_t>& pending, const CellRunner& run_cell, const CellEvents& events) {
    struct Shared {
      std::mutex lock;
      std::deque<std::size_t> queue;
      bool stopping = false;
      bool computing = true;
      std::vector<std::size_t> started;
      std::vector<std::pair<std::size_t, CellStatus>> finished;
      std::exception_ptr error;
    } shared;
    shared.queue.assign(pending.begin(), pending.end());

    auto take = [&shared](std::size_t& cell) {
      if (shared.stopping || shared.queue.empty()) return false;
      cell = shared.queue.front();
      shared.queue.pop_front();
      return true;
    };
    std::thread computer;
    if (compute_on_rank_zero_) {
      computer = std::thread([&shared, &run_cell, &take] {
        for (;;) {
          std::size_t cell = 0;
          {
            std::lock_guard<std::mutex> guard(shared.lock);
            if (!take(cell)) break;
            shared.started.push_back(cell);
          }
          try {
            const CellStatus status = run_cell(cell);
            std::lock_guard<std::mutex> guard(shared.lock);
            shared.finished.emplace_back(cell, status);
          } catch (...) {
            std::lock_guard<std::mutex> guard(shared.lock);
            shared.error = std::current_exception();
            shared.stopping = true;
            break;
          }
        }
        std::lock_guard<std::mutex> guard(shared.lock);
        shared.computing = false;
      });
    } else {
      shared.computing = false;
    }

    auto report_local_events = [&shared, &events] {
      std::vector<std::size_t> started;
      std::vector<std::pair<std::size_t, CellStatus>> finished;
      {
        std::lock_guard<std::mutex> guard(shared.lock);
        started.swap(shared.started);
        finished.swap(shared.finished);
      }
      for (const std::size_t cell : started)
        if (events.on_started) events.on_started(cell, 0);
      for (const auto& [cell, status] : finished)
        if (events.on_finished) events.on_finished(cell, 0, status);
    };

    int working = ranks_ - 1;
    std::string first_failure;
    auto pause = std::chrono::microseconds(20);
    for (;;) {
      report_local_events();
      bool computing = false;
      {
        std::lock_guard<std::mutex> guard(shared.lock);
        computing = shared.computing;
      }
      if (working == 0 && !computing) break;
      int arrived = 0;
      MPI_Status envelope;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &envelope);
      if (!arrived) {
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(1000));
        continue;
      }
      pause = std::chrono::microseconds(20);
      const int source = envelope.MPI_SOURCE;
      if (envelope.MPI_TAG == kReady) {
        long long report[2] = {-1, 0};
        MPI_Recv(report, 2, MPI_LONG_LONG, source, kReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (report[0] >= 0 && events.on_finished)
          events.on_finished(static_cast<std::size_t>(report[0]), source,
                             report[1] == 0 ? CellStatus::ok : CellStatus::error);
        std::size_t cell = 0;
        bool assigned = false;
        {
          std::lock_guard<std::mutex> guard(shared.lock);
          assigned = take(cell);
        }
        if (assigned) {
          const long long message = static_cast<long long>(cell);
          MPI_Send(&message, 1, MPI_LONG_LONG, source, kAssign, MPI_COMM_WORLD);
          if (events.on_started) events.on_started(cell, source);
        } else {
          send_empty(source, kStop);
          --working;
        }
      } else if (envelope.MPI_TAG == kFatal) {
        const std::string text = receive_text(envelope);
        if (first_failure.empty())
          first_failure = "rank " + std::to_string(source) + " on " + hosts_[static_cast<std::size_t>(source)] + ": " + text;
        std::lock_guard<std::mutex> guard(shared.lock);
        shared.stopping = true;
        --working;
      } else {
        receive_text(envelope);   // nothing else is sent to rank 0 during run_cells
      }
    }
    if (computer.joinable()) computer.join();
    report_local_events();
    if (shared.error) std::rethrow_exception(shared.error);
    if (!first_failure.empty()) throw Error(first_failure);
  }

  int rank_ = 0, ranks_ = 1;
  std::string host_;
  std::vector<std::string> hosts_;
  bool released_ = false;
  bool compute_on_rank_zero_ = true;
};

}  // namespace

std::unique_ptr<CellDispatcher> make_cell_dispatcher() {
  // Without a launcher this process runs alone exactly as a build without MPI does (MPI is not even initialised).
  if (mpi_launcher_process_count() == 0) return std::make_unique<CellDispatcher>();
  return std::make_unique<MpiDispatcher>();
}

std::string mpi_library_version() {
  char version[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  MPI_Get_library_version(version, &length);
  std::string text(version, static_cast<std::size_t>(length));
  const std::size_t end = text.find_first_of(",\n");   // "Open MPI v4.1.4, package: ..." -> "Open MPI v4.1.4"
  return text.substr(0, end);
}

}  // namespace blocklab
