// An overlay file that cannot be shown, with what is wrong in words a person can act on.
export class OverlayError extends Error {}
