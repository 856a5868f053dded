// libFuzzer's start-up hook, shared by the targets: each runs its inputs in an empty folder.
#include "FuzzSupport.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  gbx::fuzz::enterEmptyFolder();
  return 0;
}
