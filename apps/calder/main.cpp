// SPDX-License-Identifier: MIT
// calder: the command line.
//
//   calder list                      the built-in scenes
//   calder run SCENE|FILE [flags]    run a scene headless (see calder run --help)
//   calder render SCENE|FILE [flags] draw it to PNG frames and/or a GIF
//   calder window SCENE|FILE [flags] run it in a window, with the mouse
//   calder --version
//
// Exit status: 0 success, 1 the run failed, 2 bad usage or bad input; every
// error is one line on stderr, "calder: <message>".
#include <calder/render.hpp>
#include <iostream>

#include "cli.hpp"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  const int status = calder::app::main(argc, argv, std::cout, std::cerr);
  calder::release_render_caches();  // a clean exit for leak checkers
  return status;
}
