// replay --window: the translucency demos of document 000 in a GLFW window, with an
// orbit camera and a Dear ImGui overlay drawn through the RHI (app/imgui_rhi.h).
#pragma once

// True when the command line asks for the window (--window anywhere in it).
bool ReplayWindowRequested(int argc, char** argv);
// Parses the whole command line itself (the options are in replay_window.cpp) and runs
// the window until Esc, closing it, or --frames N with --screenshot. Exit codes: 0 ok,
// 1 failure, 2 usage, 3 RHI / validation-layer messages.
int RunReplayWindow(int argc, char** argv);
