#pragma once
// A spec compiled and its first gearbox's model, for tests (the test owns both).
#include <memory>
#include <stdexcept>
#include <string>

#include "driver/Driver.h"
#include "model/Model.h"

struct Compiled {
  std::unique_ptr<gbx::driver::Compilation> c;
  std::unique_ptr<gbx::rt::Model> m;
};

inline Compiled compileFirst(const std::string& text) {
  Compiled out;
  out.c = gbx::driver::compileText("t.gbx", text);
  if (!out.c->ok()) throw std::runtime_error(text + out.c->diags.renderText(out.c->sources));
  out.m = std::make_unique<gbx::rt::Model>(out.c->program, out.c->program.gearboxes[0]);
  return out;
}

// The codes of a text's diagnostics, in order, each followed by a space ("" when it checks clean).
inline std::string diagnosticCodes(const std::string& text) {
  auto c = gbx::driver::compileText("s.gbx", text);
  std::string out;
  for (const auto& d : c->diags.sorted())
    out += d.code + " ";
  return out;
}
