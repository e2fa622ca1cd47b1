// Replaces the global operator new and delete (but for the aligned forms, which the hub does not
// use and which keep the library's own) with malloc and free behind a 16-byte tag: the block's
// size and owner, so a block freed by the hub that the rig allocated (the lines the hub takes from
// the simulated Mega) is taken off the rig's count.
#include "heap_count.h"

#include <atomic>
#include <cstdlib>
#include <new>

namespace hub {
namespace heap {
namespace {

thread_local Owner current = Owner::Hub;
std::atomic<int64_t> bytes[2];
std::atomic<int64_t> blocks[2];

struct alignas(16) Tag {
  uint64_t size;
  Owner owner;
};
static_assert(sizeof(Tag) == 16, "keeps the blocks aligned as malloc's");

void* take(std::size_t size) {
  Tag* t = static_cast<Tag*>(std::malloc(sizeof(Tag) + size));
  if (!t) return nullptr;
  t->size = size;
  t->owner = current;
  int i = static_cast<int>(t->owner);
  bytes[i].fetch_add(static_cast<int64_t>(size), std::memory_order_relaxed);
  blocks[i].fetch_add(1, std::memory_order_relaxed);
  return t + 1;
}

void give(void* p) noexcept {
  if (!p) return;
  Tag* t = static_cast<Tag*>(p) - 1;
  int i = static_cast<int>(t->owner);
  bytes[i].fetch_sub(static_cast<int64_t>(t->size), std::memory_order_relaxed);
  blocks[i].fetch_sub(1, std::memory_order_relaxed);
  std::free(t);
}

void* takeOrThrow(std::size_t size) {
  void* p = take(size ? size : 1);
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace

RigScope::RigScope() : before_(current) { current = Owner::Rig; }
RigScope::~RigScope() { current = before_; }

Live live(Owner o) {
  int i = static_cast<int>(o);
  return {bytes[i].load(std::memory_order_relaxed), blocks[i].load(std::memory_order_relaxed)};
}

}  // namespace heap
}  // namespace hub

void* operator new(std::size_t size) { return hub::heap::takeOrThrow(size); }
void* operator new[](std::size_t size) { return hub::heap::takeOrThrow(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return hub::heap::take(size ? size : 1); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return hub::heap::take(size ? size : 1); }
void operator delete(void* p) noexcept { hub::heap::give(p); }
void operator delete[](void* p) noexcept { hub::heap::give(p); }
void operator delete(void* p, std::size_t) noexcept { hub::heap::give(p); }
void operator delete[](void* p, std::size_t) noexcept { hub::heap::give(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { hub::heap::give(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { hub::heap::give(p); }
