// A draped image that cannot be used: the message names the file and says what is wrong, for the
// status line. The terrain and the image already shown stay.

export class ImageError extends Error {
  /**
   * @param {string} file the image's (or its world file's) name
   * @param {string} problem what is wrong, in a person's words
   */
  constructor(file, problem) {
    super(file ? `${file}: ${problem}` : problem);
    this.name = 'ImageError';
    this.file = file;
    this.problem = problem;
  }
}
