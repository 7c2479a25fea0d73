#pragma once
// CPU seconds used so far by this whole process (every thread, user + system): with the wall
// time of a stage it tells how many cores the stage kept busy (issue 22). In a host that loads
// the module library into its own process the figure includes the host's threads.
namespace colonmap::cli {

double ProcessCpuSeconds();
// CPU seconds used so far by the calling thread alone (user + system).
double ThreadCpuSeconds();

}  // namespace colonmap::cli
