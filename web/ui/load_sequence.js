// One load at a time, and the newest wins. Starting a load (a drop, Open file…, ?src=) aborts
// the one in flight and waits for it to unwind before the new one begins, so two terrains never
// decode into the core at once and a late answer to an old load can never replace what the
// user opened since: a load that was aborted returns 'cancelled' and shows nothing.

/** The reason a load was aborted: the user's Cancel (`byUser`), or a newer load. */
export class LoadCancelled extends Error {
  constructor(byUser) {
    super(byUser ? 'loading cancelled' : 'another file was opened');
    this.name = 'AbortError';
    this.byUser = byUser;
  }
}

export class LoadSequence {
  /** @param {(busy: boolean) => void} onBusy told when loading starts and when the last load has ended */
  constructor(onBusy) {
    this.onBusy = onBusy;
    this.active = null; // { controller, done } of the newest load
  }

  /**
   * Runs `task(signal)` after the load before it has unwound. The task checks `signal` after
   * every wait and returns 'cancelled' (showing nothing) once it is aborted.
   * @param {(signal: AbortSignal) => Promise<'shown'|'failed'|'cancelled'>} task
   * @returns {Promise<'shown'|'failed'|'cancelled'>}
   */
  async run(task) {
    const previous = this.active;
    previous?.controller.abort(new LoadCancelled(false));
    const controller = new AbortController();
    const entry = { controller, done: null };
    this.active = entry;
    if (!previous) this.onBusy(true);
    entry.done = (async () => {
      await previous?.done.catch(() => {}); // its own caller reports how it ended
      return controller.signal.aborted ? 'cancelled' : task(controller.signal);
    })();
    try {
      return await entry.done;
    } finally {
      if (this.active === entry) {
        this.active = null;
        this.onBusy(false);
      }
    }
  }

  /** The Cancel button: aborts the load in flight, if any. */
  cancel() {
    this.active?.controller.abort(new LoadCancelled(true));
  }

  /** True while a load runs. */
  get busy() {
    return this.active !== null;
  }

  /** Resolves once no load runs (including loads started while waiting). */
  async idle() {
    while (this.active) await this.active.done.catch(() => {});
  }
}
