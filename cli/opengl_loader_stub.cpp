// The one OpenGL symbol the `fleetmerge` executable's static copy of OpenCV core refers to.
//
// OpenCV core's archive carries an OpenGL function loader (gl_core_3_1.cpp) whose static
// initialiser points every GL entry at a trampoline; a trampoline looks its function up through
// glXGetProcAddressARB on its first call. The executable makes no OpenGL call, yet linking
// libGLX for this one reference loads it and its X11, xcb, Xau, Xdmcp, bsd and md libraries at
// every start (~2 ms on the CI machine; docs/speed.md, "Where the time goes now"). Here the
// lookup answers "no such function", which OpenCV's loader turns into a cv::Exception
// ("Can't load OpenGL extension") should a call ever reach it.
//
// Hidden: the symbol is only for the executable's own copy of OpenCV. The commands module's
// OpenCV (a shared library) binds to the real libGLX.

extern "C" {

using GlxFunction = void (*)();

__attribute__((visibility("hidden"))) GlxFunction glXGetProcAddressARB(const unsigned char*) {
  return nullptr;
}

}  // extern "C"
