// meshsal: the process-wide device cache (see gpu_session.h).
#include "gpu/gpu_session.h"

#include <cstdlib>
#include <cstring>
#include <map>
#include <tuple>

#include "core/timer.h"
#include "gpu/vk_compute.h"

namespace meshsal::gpu {

struct CachedDevice {
  std::mutex busy;                   // held by the one lease using it
  std::unique_ptr<vk::Context> ctx;
  bool drop_when_free = false;       // release_cached_devices() found it busy
};

namespace {

using Key = std::tuple<int, bool, bool>;  // device index, validation, forced staging

struct Cache {
  std::mutex mutex;  // guards `devices` and the counters
  std::map<Key, std::shared_ptr<CachedDevice>> devices;
  uint64_t contexts_opened = 0;
  uint64_t kernels_built = 0;
  bool exit_hook = false;
};

// Never destroyed by a static destructor: the cached contexts are closed by an atexit
// hook registered after the first device was opened, so it runs before the driver's own
// exit handlers (registered while it loaded) tear it down.
Cache& cache() {
  static Cache* c = new Cache;
  return *c;
}

std::unique_ptr<vk::Context> open(int device_index, bool validation, double* seconds) {
  const Timer t;
  auto ctx = std::make_unique<vk::Context>(device_index, validation);
  *seconds = t.seconds();
  Cache& c = cache();
  std::lock_guard<std::mutex> g(c.mutex);
  c.contexts_opened++;
  return ctx;
}

}  // namespace

DeviceLease lease_cached_device(int device_index, bool validation) {
  const Key key{device_index, validation || vk::validation_requested_by_env(), vk::force_staging_by_env()};
  Cache& c = cache();
  DeviceLease lease;
  std::lock_guard<std::mutex> g(c.mutex);
  auto it = c.devices.find(key);
  if (it == c.devices.end()) return lease;
  std::unique_lock<std::mutex> busy(it->second->busy, std::try_to_lock);
  if (!busy.owns_lock() || !it->second->ctx) return lease;
  lease.cached_ = it->second;
  lease.lock_ = std::move(busy);
  lease.kernels_at_start_ = lease.cached_->ctx->kernel_cache.size();
  return lease;
}

DeviceLease lease_device(int device_index, bool validation) {
  validation = validation || vk::validation_requested_by_env();
  const Key key{device_index, validation, vk::force_staging_by_env()};
  Cache& c = cache();
  DeviceLease lease;
  std::shared_ptr<CachedDevice> slot;
  {
    std::lock_guard<std::mutex> g(c.mutex);
    auto it = c.devices.find(key);
    if (it != c.devices.end()) {
      std::unique_lock<std::mutex> l(it->second->busy, std::try_to_lock);
      if (l.owns_lock()) {
        lease.cached_ = it->second;
        lease.lock_ = std::move(l);
      }
    } else if (c.devices.size() < kMaxCachedDevices) {
      slot = std::make_shared<CachedDevice>();
      lease.lock_ = std::unique_lock<std::mutex>(slot->busy);
      lease.cached_ = slot;
      c.devices[key] = slot;  // others find it busy until it is open
    }
  }
  if (lease.cached_ && !slot) {  // a cached, open device: no start-up at all
    lease.kernels_at_start_ = lease.cached_->ctx->kernel_cache.size();
    return lease;
  }
  lease.opened_ = true;
  try {
    std::unique_ptr<vk::Context> ctx = open(device_index, validation, &lease.open_seconds_);
    if (slot) {
      slot->ctx = std::move(ctx);
      std::lock_guard<std::mutex> g(c.mutex);
      if (!c.exit_hook) c.exit_hook = std::atexit(release_cached_devices) == 0;
    } else {
      lease.own_ = std::move(ctx);
    }
  } catch (...) {
    if (slot) {  // nothing to cache: the next call tries again
      std::lock_guard<std::mutex> g(c.mutex);
      c.devices.erase(key);
    }
    throw;
  }
  return lease;
}

DeviceLease::DeviceLease(DeviceLease&& o) noexcept { *this = std::move(o); }

DeviceLease& DeviceLease::operator=(DeviceLease&& o) noexcept {
  if (this != &o) {
    release();
    cached_ = std::move(o.cached_);
    lock_ = std::move(o.lock_);
    own_ = std::move(o.own_);
    opened_ = o.opened_;
    open_seconds_ = o.open_seconds_;
    kernels_at_start_ = o.kernels_at_start_;
  }
  return *this;
}

DeviceLease::~DeviceLease() { release(); }

vk::Context& DeviceLease::context() const { return own_ ? *own_ : *cached_->ctx; }

void DeviceLease::release() {
  Cache& c = cache();
  if (own_) {
    {
      std::lock_guard<std::mutex> g(c.mutex);
      c.kernels_built += own_->kernel_cache.size();
    }
    own_.reset();
  }
  if (!cached_) return;
  bool drop = false;
  {
    std::lock_guard<std::mutex> g(c.mutex);
    if (cached_->ctx) c.kernels_built += cached_->ctx->kernel_cache.size() - kernels_at_start_;
    drop = cached_->drop_when_free;
  }
  if (drop) cached_->ctx.reset();  // release_cached_devices() asked while it was busy
  lock_.unlock();
  cached_.reset();
}

void DeviceLease::discard_if_broken(const char* error) {
  vk::Context& ctx = context();
  const bool broken = ctx.has_abandoned_work() || (error && std::strstr(error, "VK_ERROR_DEVICE_LOST"));
  if (!broken || !cached_) return;
  Cache& c = cache();
  std::lock_guard<std::mutex> g(c.mutex);
  for (auto it = c.devices.begin(); it != c.devices.end(); ++it)
    if (it->second == cached_) {
      c.devices.erase(it);
      break;
    }
  cached_->drop_when_free = true;  // closed when this lease ends
}

SessionCounters session_counters() {
  Cache& c = cache();
  std::lock_guard<std::mutex> g(c.mutex);
  SessionCounters s;
  s.contexts_opened = c.contexts_opened;
  s.kernels_built = c.kernels_built;
  s.cached = c.devices.size();
  return s;
}

void release_cached_devices() {
  Cache& c = cache();
  std::vector<std::shared_ptr<CachedDevice>> closing;
  {
    std::lock_guard<std::mutex> g(c.mutex);
    for (auto it = c.devices.begin(); it != c.devices.end();) {
      std::unique_lock<std::mutex> l(it->second->busy, std::try_to_lock);
      if (l.owns_lock()) {
        closing.push_back(it->second);
      } else {
        it->second->drop_when_free = true;
      }
      it = c.devices.erase(it);
    }
  }
  for (auto& d : closing) d->ctx.reset();  // outside the cache lock: destruction may wait
}

}  // namespace meshsal::gpu
