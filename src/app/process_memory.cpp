#include "app/process_memory.h"

#include <unistd.h>

#include <fstream>

namespace sixway::app {

uint64_t residentSetBytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t sizePages = 0, residentPages = 0;
  if (!(statm >> sizePages >> residentPages)) return 0;
  return residentPages * uint64_t(sysconf(_SC_PAGESIZE));
}

}  // namespace sixway::app
