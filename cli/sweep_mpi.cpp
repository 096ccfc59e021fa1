#include "cli/sweep_mpi.hpp"
#include <cstdlib>
#include <stdexcept>

#ifdef TERRACE_HAVE_MPI
#include "cli/engine_keys.hpp"
#include "cli/interrupt.hpp"
#include <chrono>
#include <cstdio>
#include <mpi.h>
#include <thread>
#endif

namespace terrace::cli {

bool launchedByMpi() {
    for (const char* size : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
        if (const char* v = std::getenv(size); v != nullptr && std::atoi(v) > 1) return true;
    return false;
}

#ifndef TERRACE_HAVE_MPI

bool haveMpi() {
    return false;
}

int mpiSweep(const std::filesystem::path&, const std::vector<std::string>&, const SweepOptions&) {
    throw std::runtime_error(
        "sweep: started by an MPI launcher, but this terrace was built without MPI (install "
        "libopenmpi-dev and build again); run it without mpirun, with -j N, instead");
}

#else

namespace {

constexpr int reportTag = 1, assignTag = 2;
constexpr auto pollInterval = std::chrono::milliseconds(10);

// A report travels as doubles: run, signalled, code, wall seconds, leaving.
constexpr int reportLength = 5;

class MpiWorkers final : public RemoteWorkers {
public:
    explicit MpiWorkers(int ranks) : ranks_(ranks) {}
    int count() const override { return ranks_ - 1; }

    std::optional<Report> poll() override {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, reportTag, MPI_COMM_WORLD, &flag, &status);
        if (!flag) return std::nullopt;
        double buffer[reportLength];
        MPI_Recv(buffer, reportLength, MPI_DOUBLE, status.MPI_SOURCE, reportTag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        Report r;
        r.worker = status.MPI_SOURCE;
        r.run = int(buffer[0]);
        r.exit = {buffer[1] != 0.0, int(buffer[2])};
        r.wallSeconds = buffer[3];
        r.leaving = buffer[4] != 0.0;
        return r;
    }

    void assign(int worker, int run, RunAction action) override {
        int message[2] = {run, int(action)};
        MPI_Send(message, 2, MPI_INT, worker, assignTag, MPI_COMM_WORLD);
    }

private:
    int ranks_;
};

void waitFor(MPI_Request& request) {
    int done = 0;
    while (MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done)
        std::this_thread::sleep_for(pollInterval);
}

/// Ranks 1..K-1: ask, run, report, until told there is no more or a signal arrives.
void workerLoop(const SweepPlan& plan, const SweepOptions& options) {
    const InterruptGuard guard;
    const ChildWatch watch;
    double report[reportLength] = {-1.0, 0.0, 0.0, 0.0, 0.0};
    while (true) {
        report[4] = guard.requested() ? 1.0 : 0.0;
        MPI_Request request;
        MPI_Isend(report, reportLength, MPI_DOUBLE, 0, reportTag, MPI_COMM_WORLD, &request);
        waitFor(request);
        if (report[4] != 0.0) return;
        int assignment[2] = {-1, 0};
        MPI_Irecv(assignment, 2, MPI_INT, 0, assignTag, MPI_COMM_WORLD, &request);
        waitFor(request);
        const int i = assignment[0];
        if (i < 0) return;
        const auto started = std::chrono::steady_clock::now();
        RunProcess process(plan, plan.runs[i], options.out / plan.runs[i].name,
                           RunAction(assignment[1]));
        bool forwarded = false;
        std::optional<ChildExit> exit;
        while (!(exit = process.poll())) {
            if (guard.requested() && !forwarded) process.signal(guard.signal()), forwarded = true;
            watch.wait(std::chrono::milliseconds(1000));
        }
        report[0] = i;
        report[1] = exit->signalled ? 1.0 : 0.0;
        report[2] = exit->code;
        report[3] =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    }
}

} // namespace

bool haveMpi() {
    return true;
}

int mpiSweep(const std::filesystem::path& sweepFile, const std::vector<std::string>& extraSets,
             const SweepOptions& options) {
    MPI_Init(nullptr, nullptr);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    int status = 0;
    // Every rank reads the plan (the file is on a shared file system); rank 0 alone speaks.
    SweepPlan plan;
    std::string error;
    try {
        plan = loadSweep(sweepFile, extraSets);
        if (options.strict) refuseIgnoredKeys(plan);
    } catch (const std::exception& e) {
        error = e.what();
    }
    int bad = error.empty() ? 0 : 1, anyBad = 0;
    MPI_Allreduce(&bad, &anyBad, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (anyBad) {
        if (rank == 0)
            std::fprintf(stderr, "terrace: %s\n",
                         error.empty() ? "sweep: another rank cannot read the sweep file"
                                       : error.c_str());
        MPI_Finalize();
        return 2;
    }
    if (rank == 0)
        for (const std::string& note : plan.ignoredKeys)
            std::fprintf(stderr, "terrace: warning: %s\n", asWarning(note).c_str());
    try {
        if (rank == 0) {
            MpiWorkers workers(ranks);
            status = runSweep(plan, options, &workers);
        } else {
            workerLoop(plan, options);
        }
    } catch (const std::exception& e) {
        // The other ranks would wait for this one for ever.
        std::fprintf(stderr, "terrace: sweep (rank %d): %s\n", rank, e.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    MPI_Finalize();
    return status;
}

#endif

} // namespace terrace::cli
