// SIGINT and SIGTERM as a request to stop at the next safe point (a batch boundary), so a long
// run can flush its files, write its summary and a final checkpoint before it exits.
#pragma once

namespace repose {

// Installs the handlers (idempotent). A second signal while stopping ends the process at once.
void install_stop_handlers();
// The signal that asked to stop (SIGINT or SIGTERM), or 0 while none did.
int stop_requested();

}  // namespace repose
