#include "core/parallel.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>

namespace fleetmerge {
namespace {

// Threads kept waiting between ParallelFor calls. One pair runs about ten parallel stages
// (loading, preparing, the rotation searches, two refinements, the ranking), and starting and
// joining a thread for each cost ~0.2 ms apiece on the CI VM, on the pair's critical path.
// Every task gets a worker that is idle when it is queued (or a new one), never one that is busy,
// so a ParallelFor inside a ParallelFor body cannot wait for a worker that waits for it.
class WorkerPool {
 public:
  // One ParallelFor's tasks still running (guarded by the pool's mutex).
  struct Batch {
    int running = 0;
    std::condition_variable done;
  };

  // The process's pool. Never destroyed: its idle workers wait until the process ends. A child
  // made by fork() has none of its parent's threads, so it gets a pool of its own.
  static WorkerPool& Get() {
    static std::atomic<WorkerPool*> pool{nullptr};
    WorkerPool* current = pool.load();
    if (current == nullptr || current->pid_ != getpid()) {
      static std::mutex creating;
      const std::lock_guard<std::mutex> lock(creating);
      current = pool.load();
      if (current == nullptr || current->pid_ != getpid()) {
        current = new WorkerPool();  // the parent's pool (in a child) is left as it is
        pool.store(current);
      }
    }
    return *current;
  }

  // Hands `task` of `batch` to an idle worker, or to a new thread that runs it first; false (task
  // dropped) when no thread can be started.
  bool Run(std::function<void()> task, Batch& batch) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (idle_ == 0) {
      // The new thread runs this very task, so its start-up is over before the batch is: a caller
      // that returns and then forks copies no thread half started.
      try {
        std::thread(&WorkerPool::Work, this, Task{std::move(task), &batch}).detach();
      } catch (const std::system_error&) {
        return false;
      }
    } else {
      --idle_;  // a waiting worker is now spoken for
      tasks_.push_back({std::move(task), &batch});
      wake_.notify_one();
    }
    ++batch.running;
    return true;
  }

  // Returns once every task of `batch` has run.
  void Wait(Batch& batch) {
    std::unique_lock<std::mutex> lock(mutex_);
    batch.done.wait(lock, [&] { return batch.running == 0; });
  }

 private:
  struct Task {
    std::function<void()> run;
    Batch* batch;
  };

  WorkerPool() : pid_(getpid()) {}

  // idle_ counts the workers waiting (or about to) less the tasks queued, whichever worker
  // takes which task.
  void Work(Task task) {
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    for (;;) {
      task.run();  // ParallelFor's worker: it catches what the body throws
      // Freed before the batch hears of it: once its caller returns, no worker of the batch is
      // inside the allocator, so a fork() right after (the Python module may fork) copies no
      // allocator lock a worker held. glibc's malloc guards fork() itself; AddressSanitizer's
      // allocator (clang 14) does not.
      task.run = nullptr;
      lock.lock();
      // Counted idle before its batch hears of it, so that the caller's next ParallelFor finds
      // this worker instead of starting another.
      ++idle_;
      if (--task.batch->running == 0) task.batch->done.notify_all();
      wake_.wait(lock, [this] { return !tasks_.empty(); });
      task = std::move(tasks_.front());
      tasks_.pop_front();
      lock.unlock();
    }
  }

  const pid_t pid_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Task> tasks_;
  int idle_ = 0;
};

}  // namespace

void ParallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;  // guards `failure` and `failed_index`
  std::exception_ptr failure;
  std::size_t failed_index = count;
  const auto worker = [&] {
    for (std::size_t k = next++; k < count; k = next++) {
      try {
        body(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (k < failed_index) failure = std::current_exception(), failed_index = k;
      }
    }
  };
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
  if (threads == 1) {
    worker();
  } else {
    WorkerPool& pool = WorkerPool::Get();
    WorkerPool::Batch helpers;
    // A helper that cannot be started leaves its share to the threads running (this one at
    // least).
    for (int t = 1; t < threads; ++t) {
      if (!pool.Run(worker, helpers)) break;
    }
    worker();            // this thread works too
    pool.Wait(helpers);  // on the pool the helpers were queued in
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace fleetmerge
