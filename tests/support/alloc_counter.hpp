#pragma once
// Counts the heap allocations (global operator new) made on this thread while an AllocationCount
// is alive: how tests check "no allocation per packet". The operators are replaced for the whole
// test binary (alloc_counter.cpp); outside a count they only forward to malloc / free.
namespace foresight::test {

void set_allocation_counting(bool on);
int allocations_counted();

class AllocationCount {
 public:
  explicit AllocationCount(bool on = true) : start_(allocations_counted()) {
    set_allocation_counting(on);
  }
  ~AllocationCount() { set_allocation_counting(false); }
  AllocationCount(const AllocationCount&) = delete;
  AllocationCount& operator=(const AllocationCount&) = delete;
  int allocations() const { return allocations_counted() - start_; }

 private:
  int start_;
};

}  // namespace foresight::test
